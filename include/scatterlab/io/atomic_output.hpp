#pragma once
// Nothing half-written is left behind (docs/architecture.md, "Errors"): an output is written to a temporary
// file beside its final path and renamed into place only when complete. Rename within one
// directory is atomic on POSIX, so readers see either the old file or the whole new one.

#include <filesystem>
#include <functional>
#include <ostream>
#include <span>
#include <vector>

namespace scatterlab {

class AtomicOutput {
 public:
  // Throws InputError("out", ...) when the directory of `final_path` does not exist or
  // `final_path` names a directory. Creates nothing yet.
  explicit AtomicOutput(std::filesystem::path final_path);
  AtomicOutput(const AtomicOutput&) = delete;
  AtomicOutput& operator=(const AtomicOutput&) = delete;
  // Removes the temporary file unless commit() succeeded.
  ~AtomicOutput();

  // Where to write: "<final>.tmp-<pid>-<n>" in the same directory (unique within the process).
  const std::filesystem::path& temporary_path() const { return temporary_path_; }
  const std::filesystem::path& final_path() const { return final_path_; }
  bool committed() const { return committed_; }

  // Renames the temporary file onto the final path, replacing an existing file there. Throws
  // std::runtime_error (and keeps the temporary file for the destructor to remove) on failure.
  void commit();

 private:
  std::filesystem::path final_path_;
  std::filesystem::path temporary_path_;
  bool committed_ = false;
};

// Removes the temporaries of `final_path` ("<final>.tmp-<pid>-<n>") whose process is gone, as a
// kill during the write leaves them; a temporary of a live process is kept. Returns what it
// removed.
std::vector<std::filesystem::path> remove_stale_temporaries(
    const std::filesystem::path& final_path);

// A text file (CSV, Markdown) written the same way: `body` writes to a stream in memory, whose
// text is then written whole to the temporary file (write_whole_file) and renamed into place.
// Throws as write_whole_file does (and InputError as AtomicOutput does).
void write_text_file(const std::filesystem::path& path,
                     const std::function<void(std::ostream&)>& body);

// Every output's bytes reach the disk through this one function: `path` is created (or
// truncated), `bytes` written and synced to the disk, so that a full disk, a quota, a file size
// limit or an I/O error shows here, before the rename, and not as a short file later. Throws
// std::runtime_error "cannot write '<output>': <the system's reason>", naming the output the user
// asked for (output_name), with the temporary left for its AtomicOutput to remove.
void write_whole_file(const std::filesystem::path& path, std::span<const char> bytes);

// The output a path is written for: "<final>" for a temporary "<final>.tmp-<pid>-<n>" of this
// process, the path itself otherwise. Messages name it: the user knows no temporary.
std::filesystem::path output_name(const std::filesystem::path& path);

}  // namespace scatterlab
