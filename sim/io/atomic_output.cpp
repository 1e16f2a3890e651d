#include "scatterlab/io/atomic_output.hpp"

#include <fstream>

#include <unistd.h>

#include <atomic>
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
