#include "scatterlab/io/atomic_output.hpp"

#include <fstream>

#include <signal.h>
#include <sys/types.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>

#include "scatterlab/core/error.hpp"

namespace scatterlab {

namespace {

// The process id keeps concurrent runs apart; the counter keeps outputs of one process apart.
std::filesystem::path temporary_name(const std::filesystem::path& final_path) {
  static std::atomic<unsigned> counter{0};
  std::filesystem::path name = final_path;
  name += ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  return name;
}

}  // namespace

AtomicOutput::AtomicOutput(std::filesystem::path final_path) : final_path_(std::move(final_path)) {
  constexpr const char* kAccepted = "a file path in an existing, writable directory";
  if (final_path_.empty() || !final_path_.has_filename()) {
    throw InputError("out", "'" + final_path_.string() + "' does not name a file", kAccepted);
  }
  const std::filesystem::path directory =
      final_path_.has_parent_path() ? final_path_.parent_path() : std::filesystem::path(".");
  std::error_code error;
  if (!std::filesystem::is_directory(directory, error)) {
    throw InputError("out", "directory '" + directory.string() + "' does not exist", kAccepted);
  }
  if (std::filesystem::is_directory(final_path_, error)) {
    throw InputError("out", "'" + final_path_.string() + "' is a directory", kAccepted);
  }
  temporary_path_ = temporary_name(final_path_);
}

AtomicOutput::~AtomicOutput() {
  if (!committed_) {
    std::error_code ignored;  // nothing to remove when nothing was written
    std::filesystem::remove(temporary_path_, ignored);
  }
}

void AtomicOutput::commit() {
  if (committed_) return;
  std::error_code error;
  std::filesystem::rename(temporary_path_, final_path_, error);
  if (error) {
    throw std::runtime_error("cannot move '" + temporary_path_.string() + "' to '" +
                             final_path_.string() + "': " + error.message());
  }
  committed_ = true;
}

std::vector<std::filesystem::path> remove_stale_temporaries(
    const std::filesystem::path& final_path) {
  std::vector<std::filesystem::path> removed;
  if (!final_path.has_filename()) return removed;
  const std::string prefix = final_path.filename().string() + ".tmp-";
  const std::filesystem::path directory =
      final_path.has_parent_path() ? final_path.parent_path() : std::filesystem::path(".");
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(directory, error)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    char* end = nullptr;
    const long pid = std::strtol(name.c_str() + prefix.size(), &end, 10);
    if (pid <= 0 || end == nullptr || *end != '-') continue;  // not one of ours
    if (!entry.is_regular_file(error)) continue;
    if (::kill(static_cast<pid_t>(pid), 0) == -1 && errno == ESRCH &&
        std::filesystem::remove(entry.path(), error)) {
      removed.push_back(entry.path());
    }
  }
  return removed;
}

void write_text_file(const std::filesystem::path& path,
                     const std::function<void(std::ostream&)>& body) {
  AtomicOutput output(path);
  {
    std::ofstream file(output.temporary_path());
    if (!file) throw std::runtime_error("cannot write " + output.temporary_path().string());
    body(file);
    file.flush();
    if (!file) throw std::runtime_error("failed writing " + output.temporary_path().string());
  }
  output.commit();
}

}  // namespace scatterlab
