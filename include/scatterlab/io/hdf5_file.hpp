#pragma once
// A small RAII layer over the HDF5 C API: files, groups, double datasets and scalar attributes.
// Every identifier is closed on scope exit, and every HDF5 failure becomes a std::runtime_error
// naming the file, the object and what failed (HDF5's own error printing is switched off).
// The header does not include <hdf5.h>: the library links HDF5 privately.
//
// Storage choices (they are what h5py users see):
//   strings  variable-length UTF-8, scalar dataspace: h5py returns them as str
//   booleans int8 0/1 (h5py returns numpy.int8; bool(x) works)
//   doubles  IEEE little-endian; arrays of kChunkThreshold values or more are chunked and
//            compressed (shuffle + gzip level 4), smaller ones are contiguous; rank 0 is a
//            scalar dataspace (h5py returns a numpy scalar)
// Groups, datasets and the root record creation order, so members and attributes are listed in
// the order they were written (by h5py too), not alphabetically.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace scatterlab::hdf5 {

using Id = std::int64_t;  // hid_t (checked against <hdf5.h> in the .cpp)

// Arrays with at least this many values are stored chunked and compressed.
inline constexpr std::size_t kChunkThreshold = 16384;

namespace detail {

// Owns one HDF5 identifier and closes it with the matching H5?close on scope exit.
class Handle {
 public:
  using Close = int (*)(Id);

  Handle() = default;
  Handle(Id id, Close close) noexcept : id_(id), close_(close) {}
  Handle(Handle&& other) noexcept;
  Handle& operator=(Handle&& other) noexcept;
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() { reset(); }

  Id get() const { return id_; }
  // Closes now; returns false when HDF5 reports the close failed.
  bool reset() noexcept;

 private:
  Id id_ = -1;
  Close close_ = nullptr;
};

}  // namespace detail

// A double dataset read back: its extent per dimension (empty for a scalar) and row-major values.
struct Array {
  std::vector<std::size_t> shape;
  std::vector<double> values;
};

enum class AttributeType { string, floating, signed_integer, unsigned_integer, other };

// Something that carries attributes: a group (the root included) or a dataset.
class Object {
 public:
  // Writing replaces an attribute of the same name.
  void write_string_attribute(std::string_view name, std::string_view value);
  void write_double_attribute(std::string_view name, double value);
  void write_int64_attribute(std::string_view name, std::int64_t value);
  void write_uint64_attribute(std::string_view name, std::uint64_t value);
  void write_bool_attribute(std::string_view name, bool value);  // int8 0/1

  bool has_attribute(std::string_view name) const;
  std::vector<std::string> attribute_names() const;  // in creation order where recorded
  AttributeType attribute_type(std::string_view name) const;
  std::string read_string_attribute(std::string_view name) const;    // variable or fixed length
  double read_double_attribute(std::string_view name) const;         // any integer or float
  std::int64_t read_int64_attribute(std::string_view name) const;    // any integer (bools too)
  std::uint64_t read_uint64_attribute(std::string_view name) const;  // any integer

  // "<file>:<object path>", as error messages name it.
  std::string location() const;
  const std::string& path_in_file() const { return path_; }

 protected:
  Object(detail::Handle handle, std::string file, std::string path);
  Id id() const { return handle_.get(); }
  const std::string& file() const { return file_; }
  std::string child_path(std::string_view name) const;
  void close_now() { handle_.reset(); }

 private:
  detail::Handle handle_;
  std::string file_;
  std::string path_;
};

class Dataset : public Object {
 public:
  std::vector<std::size_t> shape() const;
  Array read() const;

  // HDF5 dimension scales (the HDF5 High Level library's H5DS, which netCDF-4, h5netcdf, xarray
  // and HDFView read): this 1-D dataset becomes the scale named `name`, and is attached to
  // dimension `dim` of `data`, which is labelled `name` too.
  void make_dimension_scale(std::string_view name);
  void attach_dimension_scale(Dataset& data, unsigned dim, std::string_view name) const;
  bool is_dimension_scale() const;

 private:
  friend class Group;
  using Object::Object;
};

class Group : public Object {
 public:
  // Creates the group at `path` (relative, '/'-separated), creating missing intermediate groups.
  Group create_group(std::string_view path);
  Group open_group(std::string_view path) const;

  // A double dataset of any rank: `shape` row-major, product(shape) == values.size(); an empty
  // shape writes a rank-0 scalar.
  Dataset write_dataset(std::string_view name, std::span<const double> values,
                        const std::vector<std::size_t>& shape);
  Dataset write_dataset(std::string_view name, std::span<const double> values);  // 1-D
  // The same for integer codes (stored as little-endian int32; h5py returns numpy.int32).
  Dataset write_dataset(std::string_view name, std::span<const std::int32_t> values,
                        const std::vector<std::size_t>& shape);
  Dataset open_dataset(std::string_view path) const;
  Array read_dataset(std::string_view path) const { return open_dataset(path).read(); }

  bool has_member(std::string_view path) const;
  // Unlinks the direct member `name` (a group with everything under it, or a dataset).
  void remove_member(std::string_view name);
  std::vector<std::string> member_names() const;  // in creation order where recorded

 private:
  friend class File;
  using Object::Object;
};

// A file being written is built in memory and written to the disk whole by close(), with one
// write of ours (write_whole_file, atomic_output.hpp): a full disk, a quota or a size limit is
// then one error naming the file and the system's reason, and the destructor, on the error path,
// only frees memory. Left to HDF5, a failed write surfaces in its flush, and HDF5 1.10 then
// keeps a file it could not close, whose cleanup at exit crashes the process. The cost: a file
// being written is held in memory (once more while close() writes it).
class File {
 public:
  // Creates (truncating) a file for writing: empty on the disk until close().
  static File create(const std::filesystem::path& path);
  static File open_read_only(const std::filesystem::path& path);
  // Opens an existing file to add or replace groups (read into memory; close() writes it back
  // whole); write to a copy and rename it into place (AtomicOutput) so that a failure leaves the
  // original untouched.
  static File open_read_write(const std::filesystem::path& path);

  Group& root() { return root_; }
  const Group& root() const { return root_; }
  const std::filesystem::path& path() const { return path_; }

  // Closes now, throwing if that fails; a file opened for writing is written to the disk here.
  // The destructor closes too, but writes nothing: a file never closed is discarded. Open groups
  // and datasets of this file must be closed first.
  void close();

 private:
  File(std::filesystem::path path, detail::Handle file, Group root, bool writable);

  std::filesystem::path path_;
  detail::Handle file_;
  Group root_;     // declared after file_: closed before it
  bool writable_;  // held in memory, written by close()
};

// True when `path` is a readable HDF5 file (checks the signature only).
bool is_hdf5_file(const std::filesystem::path& path);

}  // namespace scatterlab::hdf5
