#include "scatterlab/io/output_plan.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <climits>
#include <cstring>
#include <fstream>
#include <set>
#include <system_error>
#include <utility>
#include <vector>

#include "scatterlab/core/error.hpp"
#include "scatterlab/io/atomic_output.hpp"

namespace scatterlab {
namespace fs = std::filesystem;

namespace {

// An existing output directory may take a command's files when nothing there can be someone
// else's: it is empty, or scatterlab marked it as its own (output_directory_marker).
bool holds_only_scatterlab_outputs(const fs::path& directory) {
  std::error_code error;
  if (fs::exists(directory / output_directory_marker, error)) return true;
  return fs::is_empty(directory, error) && !error;
}

constexpr const char* kDistinct = "a path distinct from every input and every other output";

bool is_control(char c) {
  const auto byte = static_cast<unsigned char>(c);
  return byte < 0x20 || byte == 0x7f;
}

// The path as it can be shown in one line of a message: control characters as '?'.
std::string printable(const std::string& text) {
  std::string shown = text;
  for (char& c : shown) {
    if (is_control(c)) c = '?';
  }
  return shown;
}

std::string quoted(const fs::path& path) {
  return fmt::format("'{}'", printable(path.native()));
}

// The directory whose filesystem would hold `path`: its nearest ancestor that exists.
fs::path nearest_existing_directory(const fs::path& path) {
  std::error_code error;
  fs::path directory = fs::absolute(path, error);
  if (error) return ".";
  directory = directory.parent_path();
  while (!fs::is_directory(directory, error) && directory.has_relative_path()) {
    directory = directory.parent_path();
  }
  return directory;
}

long filesystem_limit(const fs::path& directory, int name, long fallback) {
  const long limit = ::pathconf(directory.c_str(), name);
  return limit > 0 ? limit : fallback;
}

// Symlinks and "..", resolved as far as the path exists.
fs::path resolved(const fs::path& path) {
  std::error_code error;
  fs::path absolute = fs::absolute(path, error);
  if (error) absolute = path;
  fs::path canonical = fs::weakly_canonical(absolute, error);
  return error ? absolute.lexically_normal() : canonical;
}

// `directory` if it exists, else its nearest ancestor that does (where it would be made).
fs::path existing_directory_at_or_above(const fs::path& directory) {
  std::error_code error;
  fs::path at = fs::absolute(directory, error);
  if (error) at = directory;
  while (!fs::is_directory(at, error) && at.has_relative_path()) at = at.parent_path();
  return at;
}

// Whether this process can create a file in `directory`: it makes one (a name no other file has,
// O_EXCL) and removes it at once. Permission bits alone would not say: root ignores them, and a
// read-only mount, /proc or an ACL refuse root too. Returns 0, or the errno of the refusal.
int creation_refused(const fs::path& directory) {
  static std::atomic<unsigned> counter{0};
  for (int attempt = 0; attempt < 100; ++attempt) {
    const fs::path probe =
        directory / fmt::format(".scatterlab-write-test-{}-{}", ::getpid(), counter++);
    const int file = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
    if (file < 0 && errno == EEXIST) continue;  // another process's probe, or a stray file
    if (file < 0) return errno;
    ::close(file);
    ::unlink(probe.c_str());
    return 0;
  }
  return EEXIST;
}

}  // namespace

std::string file_type_text(fs::file_type type) {
  switch (type) {
    case fs::file_type::directory:
      return "a directory";
    case fs::file_type::block:
      return "a block device";
    case fs::file_type::character:
      return "a character device";
    case fs::file_type::fifo:
      return "a FIFO";
    case fs::file_type::socket:
      return "a socket";
    default:
      return "not a regular file";
  }
}

void check_path_text(const std::string& field, const fs::path& path) {
  const std::string& text = path.native();
  if (text.empty()) throw InputError(field, "empty path", "a file or directory name");
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (is_control(text[i])) {
      throw InputError(field,
                       fmt::format("{} holds the control character 0x{:02x} at byte {}",
                                   quoted(path), static_cast<unsigned char>(text[i]), i),
                       "a path without NUL bytes or other control characters");
    }
  }
  const fs::path directory = nearest_existing_directory(path);
  const long path_max = filesystem_limit(directory, _PC_PATH_MAX, PATH_MAX);
  const long name_max = filesystem_limit(directory, _PC_NAME_MAX, NAME_MAX);
  if (static_cast<long>(text.size()) >= path_max) {
    throw InputError(field, fmt::format("the path is {} bytes long", text.size()),
                     fmt::format("a path shorter than {} bytes (PATH_MAX here)", path_max));
  }
  for (const fs::path& component : path) {
    if (static_cast<long>(component.native().size()) > name_max) {
      throw InputError(
          field,
          fmt::format("a name in {} is {} bytes long", quoted(path), component.native().size()),
          fmt::format("names of at most {} bytes (NAME_MAX here)", name_max));
    }
  }
}

namespace {

// What same_file compares, found once per path: the device and inode of a file that exists, else
// its resolved path. Two paths are the same file exactly when their identities are equal (a path
// that exists never resolves to the same path as one that does not).
struct FileIdentity {
  bool exists = false;
  dev_t device = 0;
  ino_t inode = 0;
  fs::path path;

  explicit FileIdentity(const fs::path& of) {
    struct stat status {};
    exists = ::stat(of.c_str(), &status) == 0;
    if (exists) {
      device = status.st_dev;
      inode = status.st_ino;
    } else {
      path = resolved(of);
    }
  }

  bool operator==(const FileIdentity&) const = default;
};

}  // namespace

bool same_file(const fs::path& a, const fs::path& b) {
  return FileIdentity(a) == FileIdentity(b);
}

void OutputPlan::input(std::string field, fs::path path) {
  entries_.push_back({Kind::input, std::move(field), std::move(path)});
}

void OutputPlan::rewritten_input(std::string field, fs::path path) {
  entries_.push_back({Kind::rewritten_input, std::move(field), std::move(path)});
}

void OutputPlan::output_file(std::string field, fs::path path) {
  entries_.push_back({Kind::output_file, std::move(field), std::move(path)});
}

void OutputPlan::output_directory(std::string field, fs::path path) {
  entries_.push_back({Kind::output_directory, std::move(field), std::move(path)});
}

void OutputPlan::check() const {
  for (const Entry& entry : entries_) check_path_text(entry.field, entry.path);
  std::set<fs::path> made_directories;
  for (const Entry& entry : entries_) {
    if (entry.kind == Kind::output_directory) made_directories.insert(resolved(entry.path));
  }
  for (const Entry& entry : entries_) {
    std::error_code error;
    const fs::file_status status = fs::status(entry.path, error);
    const bool exists = fs::exists(status);
    if (entry.kind == Kind::output_directory && exists && !fs::is_directory(status)) {
      throw InputError(entry.field,
                       fmt::format("{} exists and is not a directory", quoted(entry.path)),
                       "a directory, or a path where one can be made");
    }
    if (entry.kind == Kind::output_directory && exists &&
        !holds_only_scatterlab_outputs(entry.path)) {
      throw InputError(entry.field,
                       fmt::format("{} holds files scatterlab did not write (it has no {}); they "
                                   "are left as they are",
                                   quoted(entry.path), output_directory_marker),
                       "a new or empty directory, or one scatterlab wrote its outputs into");
    }
    if (entry.kind != Kind::output_file && entry.kind != Kind::rewritten_input) continue;
    const std::string accepted =
        "a regular file to replace, or a new file in an existing directory";
    if (exists && !fs::is_regular_file(status)) {
      throw InputError(entry.field,
                       fmt::format("{} is {}", quoted(entry.path), file_type_text(status.type())),
                       accepted);
    }
    if (!entry.path.has_filename()) {
      throw InputError(entry.field, fmt::format("{} does not name a file", quoted(entry.path)),
                       accepted);
    }
    // The directory must be there, or be one this command makes.
    const fs::path parent = entry.path.has_parent_path() ? entry.path.parent_path() : fs::path(".");
    if (!fs::is_directory(parent, error) && !made_directories.contains(resolved(parent))) {
      throw InputError(
          entry.field,
          fmt::format("directory {} of {} does not exist", quoted(parent), quoted(entry.path)),
          accepted);
    }
  }
  // Each output against every input and every output registered before it: an output that
  // collides is the one named, and of two outputs the later flag.
  const auto is_input = [](Kind kind) {
    return kind == Kind::input || kind == Kind::rewritten_input;
  };
  std::vector<FileIdentity> identities;
  identities.reserve(entries_.size());
  for (const Entry& entry : entries_) identities.emplace_back(entry.path);
  for (std::size_t j = 0; j < entries_.size(); ++j) {
    for (std::size_t i = 0; i < entries_.size(); ++i) {
      if (i == j) continue;
      const Entry& first = entries_[i];
      const Entry& second = entries_[j];
      if (is_input(second.kind)) continue;           // named through the output instead
      if (!is_input(first.kind) && i > j) continue;  // each pair of outputs once
      if (!(identities[i] == identities[j])) continue;
      const std::string what = is_input(first.kind) ? "input" : "output";
      throw InputError(second.field,
                       fmt::format("{} is the same file as the {} {} ({})", quoted(second.path),
                                   what, first.field, quoted(first.path)),
                       kDistinct);
    }
  }
  // Last, as the one check that writes (a file made and removed at once): every output's
  // directory, or the one that will hold a directory still to be made, takes new files.
  std::set<fs::path> writable;
  for (const Entry& entry : entries_) {
    if (is_input(entry.kind) && entry.kind != Kind::rewritten_input) continue;
    const fs::path target = entry.kind == Kind::output_directory ? entry.path
                            : entry.path.has_parent_path()       ? entry.path.parent_path()
                                                                 : fs::path(".");
    const fs::path directory = existing_directory_at_or_above(target);
    if (writable.contains(directory)) continue;
    if (const int refusal = creation_refused(directory)) {
      throw InputError(entry.field,
                       fmt::format("cannot create files in directory {} (for {}): {}",
                                   quoted(directory), quoted(entry.path), std::strerror(refusal)),
                       "a path in a directory this user can create files in");
    }
    writable.insert(directory);
  }
}

std::vector<fs::path> OutputPlan::remove_stale_temporaries() const {
  std::vector<fs::path> removed;
  for (const Entry& entry : entries_) {
    if (entry.kind != Kind::output_file && entry.kind != Kind::rewritten_input) continue;
    for (fs::path& path : scatterlab::remove_stale_temporaries(entry.path)) {
      removed.push_back(std::move(path));
    }
  }
  return removed;
}

void make_output_directory(const fs::path& directory, const std::string& field) {
  std::error_code error;
  fs::create_directories(directory, error);
  const fs::path marker = directory / output_directory_marker;
  if (!error && !fs::exists(marker, error)) {
    std::ofstream(marker)
        << "scatterlab writes its outputs into this directory; a later run may replace them.\n";
  }
  if (error || !fs::is_regular_file(marker)) {
    throw InputError(
        field,
        fmt::format("cannot create directory {} with its marker {}: {}", quoted(directory),
                    output_directory_marker, error ? error.message() : "not written"),
        "a directory, or a path where one can be made");
  }
}

void OutputPlan::make_output_directories() const {
  for (const Entry& entry : entries_) {
    if (entry.kind == Kind::output_directory) make_output_directory(entry.path, entry.field);
  }
}

}  // namespace scatterlab
