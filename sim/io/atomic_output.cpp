#include "scatterlab/io/atomic_output.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/types.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <sstream>
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

[[noreturn]] void cannot_write(const std::filesystem::path& path, int error) {
  throw std::runtime_error("cannot write '" + output_name(path).string() +
                           "': " + std::strerror(error));
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
  std::ostringstream text;
  body(text);
  const std::string bytes = std::move(text).str();
  write_whole_file(output.temporary_path(), bytes);
  output.commit();
}

void write_whole_file(const std::filesystem::path& path, std::span<const char> bytes) {
  const int file = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (file < 0) cannot_write(path, errno);
  std::size_t written = 0;
  while (written < bytes.size()) {
    const ssize_t count = ::write(file, bytes.data() + written, bytes.size() - written);
    if (count < 0 && errno == EINTR) continue;
    if (count <= 0) {
      const int error = count < 0 ? errno : EIO;
      ::close(file);
      cannot_write(path, error);
    }
    written += static_cast<std::size_t>(count);
  }
  // Some filesystems (NFS, delayed allocation) report a full disk only when the data is synced.
  if (::fsync(file) != 0 && errno != EINVAL) {
    const int error = errno;
    ::close(file);
    cannot_write(path, error);
  }
  if (::close(file) != 0 && errno != EINTR) cannot_write(path, errno);
}

std::filesystem::path output_name(const std::filesystem::path& path) {
  const std::string name = path.filename().string();
  const std::string marker = ".tmp-" + std::to_string(::getpid()) + "-";
  const std::size_t at = name.rfind(marker);
  if (at == std::string::npos || at == 0) return path;
  const std::string counter = name.substr(at + marker.size());
  if (counter.empty() || counter.find_first_not_of("0123456789") != std::string::npos) {
    return path;
  }
  return path.parent_path() / name.substr(0, at);
}

}  // namespace scatterlab
