#pragma once
// What a command will read and write, declared before any work, so that no run destroys a file
// it did not mean to write: every output must be distinct from every other output and from every
// input (compared as the files they resolve to, by inode and device, not as spellings), an
// output file must be a regular file or not exist yet (never a directory, device, FIFO or
// socket), every path must be printable text the filesystem can hold, and this process must be
// able to create files where each output goes (tried, not read from permission bits).
//
//   OutputPlan plan;
//   plan.input("--scene", scene);
//   plan.output_file("--out", out);
//   plan.output_file("--checkpoint", checkpoint);
//   plan.check();  // InputError naming the flag, before anything is read or written

#include <filesystem>
#include <string>
#include <vector>

namespace scatterlab {

// Throws InputError(field) when `path` is empty, holds a NUL byte or another control character,
// or has a component longer than the filesystem's NAME_MAX or a length over its PATH_MAX.
void check_path_text(const std::string& field, const std::filesystem::path& path);

// The same file: by inode and device when both exist, else by their resolved absolute paths.
bool same_file(const std::filesystem::path& a, const std::filesystem::path& b);

// What a file of this type is called in messages: "a directory", "a FIFO", ... ("not a regular
// file" for the rest).
std::string file_type_text(std::filesystem::file_type type);

// The file that marks a directory as one scatterlab writes its outputs into: a later run may
// replace the files there (a re-run of a report, a sweep that skips what is done), and no run
// writes into a directory that holds other files without it.
inline constexpr const char* output_directory_marker = ".scatterlab-outputs";

// Makes `directory` with its missing parents if it is not there, and leaves the marker in it;
// throws InputError(field) when it cannot. OutputPlan::make_output_directories calls it for each
// output directory; a writer that makes its directory when it writes (validate) calls it itself.
void make_output_directory(const std::filesystem::path& directory, const std::string& field);

class OutputPlan {
 public:
  // A file the command reads.
  void input(std::string field, std::filesystem::path path);
  // A file the command reads and then replaces with a new version (`fit` adds to its input): an
  // input to every other output, and a regular file like an output.
  void rewritten_input(std::string field, std::filesystem::path path);
  // A file the command writes whole (replacing one there): HDF5, CSV, image, checkpoint.
  void output_file(std::string field, std::filesystem::path path);
  // A directory the command writes files into, under names it chooses (created if missing). Its
  // files may replace only what scatterlab wrote there: an existing directory must be empty or
  // hold the marker output_directory_marker, which make_output_directories leaves in each.
  void output_directory(std::string field, std::filesystem::path path);

  // Throws InputError naming the first offending field. Reads the filesystem; the one trace it
  // leaves is a file made and removed at once in each output directory, to know it takes files.
  void check() const;

  // Removes temporaries "<output>.tmp-<pid>-<n>" (atomic_output.hpp) of every output file whose
  // process is gone: a run killed while writing leaves them. Returns what it removed.
  std::vector<std::filesystem::path> remove_stale_temporaries() const;

  // Makes every output directory that is missing, with its missing parents, and leaves the
  // marker in each; throws InputError naming its field when one cannot be made. After check(), and
  // after the inputs are read, so that bad input leaves nothing: every command that writes into a
  // directory makes it this way.
  void make_output_directories() const;

 private:
  enum class Kind { input, rewritten_input, output_file, output_directory };
  struct Entry {
    Kind kind;
    std::string field;
    std::filesystem::path path;
  };
  std::vector<Entry> entries_;
};

}  // namespace scatterlab
