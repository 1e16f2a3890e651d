#include "scatterlab/io/hdf5_file.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <hdf5.h>
#include <hdf5_hl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string_view>
#include <type_traits>
#include <utility>

#include "scatterlab/core/memory_budget.hpp"
#include "scatterlab/io/atomic_output.hpp"

namespace scatterlab::hdf5 {

static_assert(std::is_same_v<hid_t, Id>, "hdf5::Id must be hid_t");
static_assert(std::is_same_v<herr_t, int>, "detail::Handle::Close must match H5?close");

namespace {

using detail::Handle;

// HDF5 prints its error stack to stderr by default; we report through exceptions instead.
// The setting is per thread in thread-safe builds, so every entry point calls this.
void silence_error_printing() {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

// The innermost (most specific) message on HDF5's error stack, which is then cleared.
std::string take_error_detail() {
  std::string detail;
  auto innermost = [](unsigned n, const H5E_error2_t* error, void* data) -> herr_t {
    if (n == 0 && error->desc != nullptr) *static_cast<std::string*>(data) = error->desc;
    return 0;
  };
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, innermost, &detail);
  H5Eclear2(H5E_DEFAULT);
  return detail;
}

[[noreturn]] void fail(std::string_view what, const std::string& where) {
  std::string message = "HDF5: cannot " + std::string(what) + " (" + where + ")";
  const std::string detail = take_error_detail();
  if (!detail.empty()) message += ": " + detail;
  throw std::runtime_error(message);
}

hid_t check_id(hid_t id, std::string_view what, const std::string& where) {
  if (id < 0) fail(what, where);
  return id;
}

void check_status(herr_t status, std::string_view what, const std::string& where) {
  if (status < 0) fail(what, where);
}

bool check_tri(htri_t value, std::string_view what, const std::string& where) {
  if (value < 0) fail(what, where);
  return value > 0;
}

std::string in_quotes(std::string_view name) {
  std::string text = "'";  // appended, not "'" + name: GCC 12 -Wrestrict misfires on that
  text += name;
  text += '\'';
  return text;
}

Handle scalar_space() {
  return Handle(check_id(H5Screate(H5S_SCALAR), "create a scalar dataspace", "memory"), H5Sclose);
}

Handle utf8_string_type(size_t size) {
  Handle type(check_id(H5Tcopy(H5T_C_S1), "copy the string type", "memory"), H5Tclose);
  check_status(H5Tset_size(type.get(), size), "size the string type", "memory");
  check_status(H5Tset_cset(type.get(), H5T_CSET_UTF8), "set UTF-8 on the string type", "memory");
  return type;
}

// Creation order is recorded and indexed so that listings follow the order of writing.
constexpr unsigned kCreationOrder = H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED;

Handle group_creation_plist(hid_t cls) {
  Handle plist(check_id(H5Pcreate(cls), "create a property list", "memory"), H5Pclose);
  check_status(H5Pset_link_creation_order(plist.get(), kCreationOrder), "track link creation order",
               "memory");
  check_status(H5Pset_attr_creation_order(plist.get(), kCreationOrder),
               "track attribute creation order", "memory");
  return plist;
}

// Chunks hold whole trailing dimensions where they can and stay near 1 MiB of doubles, so that
// compression works on long runs of neighbouring bins.
std::vector<hsize_t> chunk_shape(const std::vector<std::size_t>& shape) {
  constexpr std::size_t kChunkValues = 131072;
  std::vector<hsize_t> chunk(shape.begin(), shape.end());
  std::size_t values = 1;
  for (const std::size_t extent : shape) values *= extent;
  for (auto& extent : chunk) {
    if (values <= kChunkValues) break;
    const std::size_t others = values / extent;
    extent = std::max<std::size_t>(1, kChunkValues / others);
    values = others * extent;
  }
  return chunk;
}

bool compression_available() {
  return H5Zfilter_avail(H5Z_FILTER_DEFLATE) > 0 && H5Zfilter_avail(H5Z_FILTER_SHUFFLE) > 0;
}

Handle dataset_creation_plist(const std::vector<std::size_t>& shape, std::size_t values,
                              const std::string& where) {
  Handle plist(check_id(H5Pcreate(H5P_DATASET_CREATE), "create a property list", where), H5Pclose);
  check_status(H5Pset_attr_creation_order(plist.get(), kCreationOrder),
               "track attribute creation order", where);
  if (!shape.empty() && values >= kChunkThreshold && compression_available()) {
    const std::vector<hsize_t> chunk = chunk_shape(shape);
    check_status(H5Pset_chunk(plist.get(), static_cast<int>(chunk.size()), chunk.data()),
                 "set the chunk shape", where);
    check_status(H5Pset_shuffle(plist.get()), "enable the shuffle filter", where);
    check_status(H5Pset_deflate(plist.get(), 4), "enable gzip compression", where);
  }
  return plist;
}

void delete_attribute_if_present(hid_t object, const std::string& name, const std::string& where) {
  if (check_tri(H5Aexists(object, name.c_str()), "look up attribute " + in_quotes(name), where)) {
    check_status(H5Adelete(object, name.c_str()), "replace attribute " + in_quotes(name), where);
  }
}

void write_attribute(hid_t object, std::string_view name, hid_t file_type, hid_t memory_type,
                     const void* value, const std::string& where) {
  const std::string key(name);
  const std::string what = "write attribute " + in_quotes(name);
  delete_attribute_if_present(object, key, where);
  const Handle space = scalar_space();
  const Handle attribute(
      check_id(H5Acreate2(object, key.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT),
               what, where),
      H5Aclose);
  check_status(H5Awrite(attribute.get(), memory_type, value), what, where);
}

Handle open_attribute(hid_t object, std::string_view name, const std::string& where) {
  const std::string key(name);
  return Handle(check_id(H5Aopen(object, key.c_str(), H5P_DEFAULT),
                         "open attribute " + in_quotes(name), where),
                H5Aclose);
}

H5T_class_t attribute_class(hid_t attribute, std::string_view name, const std::string& where) {
  const Handle type(check_id(H5Aget_type(attribute), "get the type of " + in_quotes(name), where),
                    H5Tclose);
  return H5Tget_class(type.get());
}

// Attributes written here are scalars; a one-value simple dataspace (other writers) is fine too.
void require_single_value(hid_t attribute, std::string_view name, const std::string& where) {
  const Handle space(
      check_id(H5Aget_space(attribute), "get the dataspace of " + in_quotes(name), where),
      H5Sclose);
  const hssize_t points = H5Sget_simple_extent_npoints(space.get());
  if (points != 1) {
    throw std::runtime_error("HDF5: attribute " + in_quotes(name) + " holds " +
                             std::to_string(points) + " values, expected one (" + where + ")");
  }
}

template <typename T>
T read_numeric_attribute(hid_t object, std::string_view name, hid_t memory_type, bool accept_float,
                         const std::string& where) {
  const Handle attribute = open_attribute(object, name, where);
  const H5T_class_t type_class = attribute_class(attribute.get(), name, where);
  if (type_class != H5T_INTEGER && !(accept_float && type_class == H5T_FLOAT)) {
    throw std::runtime_error("HDF5: attribute " + in_quotes(name) + " is not " +
                             (accept_float ? "a number" : "an integer") + " (" + where + ")");
  }
  require_single_value(attribute.get(), name, where);
  T value{};
  check_status(H5Aread(attribute.get(), memory_type, &value), "read attribute " + in_quotes(name),
               where);
  return value;
}

// A link's or attribute's name, with its creation order where the file recorded one.
struct ListedName {
  std::string name;
  bool has_order = false;
  std::int64_t order = 0;
};

// Collects each name HDF5 lists, of links (H5L_info_t) and attributes (H5A_info_t) alike.
template <class Info>
herr_t collect_listed(hid_t, const char* name, const Info* info, void* data) {
  static_cast<std::vector<ListedName>*>(data)->push_back(
      {name, info->corder_valid != 0, static_cast<std::int64_t>(info->corder)});
  return 0;
}

// The names in creation order where the file recorded it (every file the program writes), and by
// name where it did not (files from other writers). They are listed in HDF5's own ("native")
// order: in any other, HDF5 1.10 first builds a table of every link or attribute, and frees
// entries it never set when a damaged file stops it half way (a crash:
// tests/fuzz/libhdf5/dense-link-free.h5). So the order is the program's sort, not HDF5's.
std::vector<std::string> sorted_names(std::vector<ListedName> listed) {
  const bool ordered =
      std::all_of(listed.begin(), listed.end(), [](const ListedName& n) { return n.has_order; });
  std::sort(listed.begin(), listed.end(), [ordered](const ListedName& a, const ListedName& b) {
    return ordered ? a.order < b.order : a.name < b.name;
  });
  std::vector<std::string> names;
  names.reserve(listed.size());
  for (ListedName& n : listed) names.push_back(std::move(n.name));
  return names;
}

std::vector<std::string> split_path(std::string_view path) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (start <= path.size()) {
    const std::size_t end = std::min(path.find('/', start), path.size());
    if (end > start) parts.emplace_back(path.substr(start, end - start));
    start = end + 1;
  }
  return parts;
}

// Refuses a path that passes through an external link: a file is read for what it holds, and a
// link to another file would read a tally (or anything) from somewhere the user did not name.
void refuse_external_links(hid_t group, std::string_view path, const std::string& where) {
  std::string prefix;
  for (const std::string& part : split_path(path)) {
    prefix += (prefix.empty() ? "" : "/") + part;
    H5L_info_t link{};
    if (H5Lget_info(group, prefix.c_str(), &link, H5P_DEFAULT) < 0) return;  // opening says why
    if (link.type == H5L_TYPE_EXTERNAL) {
      throw std::runtime_error(fmt::format(
          "HDF5: {} is a link to another file (external links are not followed)", where));
    }
  }
}

}  // namespace

namespace detail {

Handle::Handle(Handle&& other) noexcept
    : id_(std::exchange(other.id_, -1)), close_(std::exchange(other.close_, nullptr)) {}

Handle& Handle::operator=(Handle&& other) noexcept {
  if (this != &other) {
    reset();
    id_ = std::exchange(other.id_, -1);
    close_ = std::exchange(other.close_, nullptr);
  }
  return *this;
}

bool Handle::reset() noexcept {
  bool closed = true;
  if (id_ >= 0 && close_ != nullptr) closed = close_(id_) >= 0;
  id_ = -1;
  close_ = nullptr;
  return closed;
}

}  // namespace detail

// ---------------------------------------------------------------------------------------------
// Object: attributes

Object::Object(Handle handle, std::string file, std::string path)
    : handle_(std::move(handle)), file_(std::move(file)), path_(std::move(path)) {}

std::string Object::location() const {
  return file_ + ":" + path_;
}

std::string Object::child_path(std::string_view name) const {
  return (path_ == "/" ? "/" : path_ + "/") + std::string(name);
}

void Object::write_string_attribute(std::string_view name, std::string_view value) {
  const Handle type = utf8_string_type(H5T_VARIABLE);
  const std::string text(value);
  const char* pointer = text.c_str();
  write_attribute(id(), name, type.get(), type.get(), &pointer, location());
}

void Object::write_double_attribute(std::string_view name, double value) {
  write_attribute(id(), name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value, location());
}

void Object::write_int64_attribute(std::string_view name, std::int64_t value) {
  write_attribute(id(), name, H5T_STD_I64LE, H5T_NATIVE_INT64, &value, location());
}

void Object::write_uint64_attribute(std::string_view name, std::uint64_t value) {
  write_attribute(id(), name, H5T_STD_U64LE, H5T_NATIVE_UINT64, &value, location());
}

void Object::write_bool_attribute(std::string_view name, bool value) {
  const std::int8_t stored = value ? 1 : 0;
  write_attribute(id(), name, H5T_STD_I8LE, H5T_NATIVE_INT8, &stored, location());
}

bool Object::has_attribute(std::string_view name) const {
  const std::string key(name);
  return check_tri(H5Aexists(id(), key.c_str()), "look up attribute " + in_quotes(name),
                   location());
}

std::vector<std::string> Object::attribute_names() const {
  std::vector<ListedName> listed;
  check_status(H5Aiterate2(id(), H5_INDEX_NAME, H5_ITER_NATIVE, nullptr, collect_listed<H5A_info_t>,
                           &listed),
               "list attributes", location());
  return sorted_names(std::move(listed));
}

AttributeType Object::attribute_type(std::string_view name) const {
  const Handle attribute = open_attribute(id(), name, location());
  const Handle type(
      check_id(H5Aget_type(attribute.get()), "get the type of " + in_quotes(name), location()),
      H5Tclose);
  switch (H5Tget_class(type.get())) {
    case H5T_STRING:
      return AttributeType::string;
    case H5T_FLOAT:
      return AttributeType::floating;
    case H5T_INTEGER:
      return H5Tget_sign(type.get()) == H5T_SGN_NONE ? AttributeType::unsigned_integer
                                                     : AttributeType::signed_integer;
    default:
      return AttributeType::other;
  }
}

std::string Object::read_string_attribute(std::string_view name) const {
  const std::string where = location();
  const std::string what = "read attribute " + in_quotes(name);
  const Handle attribute = open_attribute(id(), name, where);
  const Handle file_type(check_id(H5Aget_type(attribute.get()), what, where), H5Tclose);
  if (H5Tget_class(file_type.get()) != H5T_STRING) {
    throw std::runtime_error("HDF5: attribute " + in_quotes(name) + " is not a string (" + where +
                             ")");
  }
  require_single_value(attribute.get(), name, where);

  if (check_tri(H5Tis_variable_str(file_type.get()), what, where)) {
    const Handle memory_type = utf8_string_type(H5T_VARIABLE);
    char* text = nullptr;
    check_status(H5Aread(attribute.get(), memory_type.get(), &text), what, where);
    std::string value = text != nullptr ? text : "";
    H5free_memory(text);
    return value;
  }
  // Fixed length (other writers): read the bytes as stored, then drop the padding.
  const std::size_t size = H5Tget_size(file_type.get());
  std::string buffer(size, '\0');
  check_status(H5Aread(attribute.get(), file_type.get(), buffer.data()), what, where);
  buffer.resize(std::min(buffer.find('\0'), buffer.size()));
  if (H5Tget_strpad(file_type.get()) == H5T_STR_SPACEPAD) {
    buffer.erase(buffer.find_last_not_of(' ') + 1);
  }
  return buffer;
}

double Object::read_double_attribute(std::string_view name) const {
  return read_numeric_attribute<double>(id(), name, H5T_NATIVE_DOUBLE, true, location());
}

std::int64_t Object::read_int64_attribute(std::string_view name) const {
  return read_numeric_attribute<std::int64_t>(id(), name, H5T_NATIVE_INT64, false, location());
}

std::uint64_t Object::read_uint64_attribute(std::string_view name) const {
  return read_numeric_attribute<std::uint64_t>(id(), name, H5T_NATIVE_UINT64, false, location());
}

// ---------------------------------------------------------------------------------------------
// Dataset

std::vector<std::size_t> Dataset::shape() const {
  const Handle space(check_id(H5Dget_space(id()), "get the dataspace", location()), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank < 0) fail("get the rank", location());
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  check_status(H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr), "get the shape",
               location());
  return {dims.begin(), dims.end()};
}

namespace {

// A stored chunk inflates at most 1032-fold under deflate (its limit, for a run of one byte), and
// shuffle does not compress: a dataset that declares more than twice that of what the file
// stores is a damaged or hostile file, whatever the memory.
constexpr std::uint64_t kMostInflation = 2 * 1032;
// Contiguous, compact and scalar datasets store what they declare; this absorbs their headers.
constexpr std::uint64_t kStorageSlack = 64 * 1024;

// Before the values are allocated: the declared shape must be one the file can hold and the
// process can afford (core/memory_budget.hpp).
void check_declared_size(hid_t dataset, const std::vector<std::size_t>& shape,
                         const std::string& where) {
  const std::uint64_t values = value_count(shape);
  const std::string extents = fmt::format("{}", fmt::join(shape, " x "));
  const std::uint64_t bytes = saturating_product(values, sizeof(double));
  const std::uint64_t stored = H5Dget_storage_size(dataset);
  if (bytes > saturating_product(stored, kMostInflation) + kStorageSlack) {
    throw std::runtime_error(fmt::format(
        "HDF5: dataset declares shape [{}] ({} values, {}) but the file stores {} of it, more "
        "than deflate can inflate ({})",
        extents, values, format_bytes(bytes), format_bytes(stored), where));
  }
  MemoryEstimate need;
  need.add(fmt::format("dataset of shape [{}]", extents), bytes);
  check_memory(need, where, "smaller datasets");
}

}  // namespace

Array Dataset::read() const {
  const Handle type(check_id(H5Dget_type(id()), "get the type", location()), H5Tclose);
  const H5T_class_t type_class = H5Tget_class(type.get());
  if (type_class != H5T_FLOAT && type_class != H5T_INTEGER) {
    throw std::runtime_error("HDF5: dataset is not numeric (" + location() + ")");
  }
  Array array;
  array.shape = shape();
  check_declared_size(id(), array.shape, location());
  std::size_t values = 1;
  for (const std::size_t extent : array.shape) values *= extent;
  array.values.resize(values);
  if (values > 0) {
    check_status(
        H5Dread(id(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, array.values.data()),
        "read the dataset", location());
  }
  return array;
}

void Dataset::make_dimension_scale(std::string_view name) {
  silence_error_printing();
  check_status(H5DSset_scale(id(), std::string(name).c_str()), "make a dimension scale",
               location());
}

void Dataset::attach_dimension_scale(Dataset& data, unsigned dim, std::string_view name) const {
  silence_error_printing();
  check_status(H5DSattach_scale(data.id(), id(), dim), "attach the dimension scale " + location(),
               data.location());
  check_status(H5DSset_label(data.id(), dim, std::string(name).c_str()), "label a dimension",
               data.location());
}

bool Dataset::is_dimension_scale() const {
  silence_error_printing();
  return check_tri(H5DSis_scale(id()), "tell a dimension scale", location());
}

// ---------------------------------------------------------------------------------------------
// Group

Group Group::create_group(std::string_view path) {
  const std::vector<std::string> parts = split_path(path);
  if (parts.empty()) {
    throw std::invalid_argument("HDF5: empty group path (" + location() + ")");
  }
  const Handle plist = group_creation_plist(H5P_GROUP_CREATE);
  std::string relative;
  Handle current;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    relative += (i == 0 ? "" : "/") + parts[i];
    const std::string where = file() + ":" + child_path(relative);
    const hid_t parent = i == 0 ? id() : current.get();
    const bool last = i + 1 == parts.size();
    // Intermediate groups may exist already; the group asked for must not.
    if (!last && check_tri(H5Lexists(parent, parts[i].c_str(), H5P_DEFAULT), "look up", where)) {
      current = Handle(
          check_id(H5Gopen2(parent, parts[i].c_str(), H5P_DEFAULT), "open group", where), H5Gclose);
    } else {
      current = Handle(
          check_id(H5Gcreate2(parent, parts[i].c_str(), H5P_DEFAULT, plist.get(), H5P_DEFAULT),
                   "create group", where),
          H5Gclose);
    }
  }
  return Group(std::move(current), file(), child_path(relative));
}

Group Group::open_group(std::string_view path) const {
  const std::string key(path);
  const std::string full = child_path(path);
  refuse_external_links(id(), path, file() + ":" + full);
  return Group(
      Handle(check_id(H5Gopen2(id(), key.c_str(), H5P_DEFAULT), "open group", file() + ":" + full),
             H5Gclose),
      file(), full);
}

namespace {

// One writer for every element type: `file_type` is what the file stores, `memory_type` what
// `values` points at.
Handle write_array(hid_t group, const std::string& key, const std::string& where, hid_t file_type,
                   hid_t memory_type, const void* values, std::size_t count,
                   const std::vector<std::size_t>& shape) {
  std::size_t expected = 1;
  for (const std::size_t extent : shape) expected *= extent;
  if (expected != count) {
    throw std::invalid_argument("HDF5: dataset shape holds " + std::to_string(expected) +
                                " values but " + std::to_string(count) + " were given (" + where +
                                ")");
  }
  const std::vector<hsize_t> dims(shape.begin(), shape.end());
  const Handle space =
      shape.empty()
          ? scalar_space()
          : Handle(check_id(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr),
                            "create the dataspace", where),
                   H5Sclose);
  const Handle plist = dataset_creation_plist(shape, count, where);
  Handle dataset(check_id(H5Dcreate2(group, key.c_str(), file_type, space.get(), H5P_DEFAULT,
                                     plist.get(), H5P_DEFAULT),
                          "create dataset", where),
                 H5Dclose);
  if (count > 0) {
    check_status(H5Dwrite(dataset.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values),
                 "write dataset", where);
  }
  return dataset;
}

}  // namespace

Dataset Group::write_dataset(std::string_view name, std::span<const double> values,
                             const std::vector<std::size_t>& shape) {
  const std::string full = child_path(name);
  return Dataset(write_array(id(), std::string(name), file() + ":" + full, H5T_IEEE_F64LE,
                             H5T_NATIVE_DOUBLE, values.data(), values.size(), shape),
                 file(), full);
}

Dataset Group::write_dataset(std::string_view name, std::span<const std::int32_t> values,
                             const std::vector<std::size_t>& shape) {
  const std::string full = child_path(name);
  return Dataset(write_array(id(), std::string(name), file() + ":" + full, H5T_STD_I32LE,
                             H5T_NATIVE_INT32, values.data(), values.size(), shape),
                 file(), full);
}

Dataset Group::write_dataset(std::string_view name, std::span<const double> values) {
  return write_dataset(name, values, {values.size()});
}

Dataset Group::open_dataset(std::string_view path) const {
  const std::string key(path);
  const std::string full = child_path(path);
  refuse_external_links(id(), path, file() + ":" + full);
  return Dataset(Handle(check_id(H5Dopen2(id(), key.c_str(), H5P_DEFAULT), "open dataset",
                                 file() + ":" + full),
                        H5Dclose),
                 file(), full);
}

bool Group::has_member(std::string_view path) const {
  // H5Lexists needs every intermediate link to exist, so walk the path one link at a time.
  std::string prefix;
  for (const std::string& part : split_path(path)) {
    prefix += (prefix.empty() ? "" : "/") + part;
    if (!check_tri(H5Lexists(id(), prefix.c_str(), H5P_DEFAULT), "look up",
                   file() + ":" + child_path(prefix))) {
      return false;
    }
  }
  return !prefix.empty();
}

void Group::remove_member(std::string_view name) {
  const std::string key(name);
  check_status(H5Ldelete(id(), key.c_str(), H5P_DEFAULT), "remove member",
               file() + ":" + child_path(name));
}

std::vector<std::string> Group::member_names() const {
  std::vector<ListedName> listed;
  check_status(
      H5Literate(id(), H5_INDEX_NAME, H5_ITER_NATIVE, nullptr, collect_listed<H5L_info_t>, &listed),
      "list members", location());
  return sorted_names(std::move(listed));
}

// ---------------------------------------------------------------------------------------------
// File

File::File(std::filesystem::path path, Handle file, Group root, bool writable)
    : path_(std::move(path)), file_(std::move(file)), root_(std::move(root)), writable_(writable) {}

namespace {

// HDF5's core driver without a backing store: the file lives in memory, grown in steps of this
// many bytes, and HDF5 itself never writes to the disk.
constexpr std::size_t kMemoryIncrement = std::size_t{4} << 20;

Handle in_memory_access(const std::string& where) {
  Handle plist(check_id(H5Pcreate(H5P_FILE_ACCESS), "create a property list", where), H5Pclose);
  check_status(H5Pset_fapl_core(plist.get(), kMemoryIncrement, false), "hold the file in memory",
               where);
  return plist;
}

// HDF5 1.10.8 hangs, or reads past its buffers, on a damaged global heap collection (where it
// keeps variable-length strings: HDF5 File Format Specification 2.0, §III.E), and it reads one
// whenever a string attribute is read. So every collection is walked before the file is opened:
// each object must end inside its collection, and each collection inside the file. A collection
// is "GCOL", version 1, three reserved bytes and its size (8-byte lengths, as the library
// writes); then objects of a 2-byte index, 2-byte count, 4 reserved bytes and an 8-byte size,
// their data padded to 8 bytes. Object 0 is the free space, and its size counts its header.
void require_sound_global_heaps(const std::filesystem::path& path, const std::string& where) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return;  // H5Fopen says why
  struct stat status {};
  if (::fstat(fd, &status) != 0 || !S_ISREG(status.st_mode) || status.st_size == 0) {
    ::close(fd);
    return;
  }
  const auto size = static_cast<std::uint64_t>(status.st_size);
  void* map = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE, fd, 0);
  ::close(fd);
  if (map == MAP_FAILED) return;
  const std::string_view bytes(static_cast<const char*>(map), size);
  const auto little_endian = [&](std::uint64_t at, int width) {
    std::uint64_t value = 0;
    for (int i = width - 1; i >= 0; --i) {
      const std::uint64_t k = at + static_cast<std::uint64_t>(i);
      value = value << 8 | (k < size ? static_cast<std::uint8_t>(bytes[k]) : 0u);
    }
    return value;
  };
  constexpr std::uint64_t header = 16, object_header = 16;
  std::optional<std::uint64_t> damaged;
  for (std::size_t at = bytes.find("GCOL"); at != std::string_view::npos && !damaged;
       at = bytes.find("GCOL", at + 1)) {
    if (little_endian(at + 4, 1) != 1) continue;  // not a collection (HDF5 refuses the version)
    const std::uint64_t length = little_endian(at + 8, 8);
    if (length < header || length > size - at) {
      damaged = at;
      break;
    }
    const std::uint64_t end = at + length;
    for (std::uint64_t p = at + header; end - p >= object_header;) {
      const std::uint64_t index = little_endian(p, 2), object = little_endian(p + 8, 8);
      if (object > end - p) {
        damaged = at;
        break;
      }
      const std::uint64_t need =
          index > 0 ? object_header + ((object + 7) & ~std::uint64_t{7}) : object;
      if (need == 0 || need > end - p) {
        damaged = at;
        break;
      }
      p += need;
    }
  }
  ::munmap(map, size);
  if (damaged) {
    throw std::runtime_error(fmt::format(
        "HDF5: cannot open file ({}): its global heap (the store of its strings) at byte {} is "
        "damaged: an object runs past its collection or the collection past the file",
        where, *damaged));
  }
}

}  // namespace

File File::create(const std::filesystem::path& path) {
  silence_error_printing();
  const std::string name = path.string();
  write_whole_file(path, {});  // the file is there (and can be made) from now on
  const Handle plist = group_creation_plist(H5P_FILE_CREATE);
  const Handle access = in_memory_access(name);
  Handle file(check_id(H5Fcreate(name.c_str(), H5F_ACC_TRUNC, plist.get(), access.get()),
                       "create file", name),
              H5Fclose);
  Handle root(check_id(H5Gopen2(file.get(), "/", H5P_DEFAULT), "open the root group", name),
              H5Gclose);
  return File(path, std::move(file), Group(std::move(root), name, "/"), true);
}

File File::open_read_only(const std::filesystem::path& path) {
  silence_error_printing();
  const std::string name = path.string();
  require_sound_global_heaps(path, name);
  Handle file(check_id(H5Fopen(name.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), "open file", name),
              H5Fclose);
  Handle root(check_id(H5Gopen2(file.get(), "/", H5P_DEFAULT), "open the root group", name),
              H5Gclose);
  return File(path, std::move(file), Group(std::move(root), name, "/"), false);
}

File File::open_read_write(const std::filesystem::path& path) {
  silence_error_printing();
  const std::string name = path.string();
  require_sound_global_heaps(path, name);
  const Handle access = in_memory_access(name);
  Handle file(
      check_id(H5Fopen(name.c_str(), H5F_ACC_RDWR, access.get()), "open file for writing", name),
      H5Fclose);
  Handle root(check_id(H5Gopen2(file.get(), "/", H5P_DEFAULT), "open the root group", name),
              H5Gclose);
  return File(path, std::move(file), Group(std::move(root), name, "/"), true);
}

void File::close() {
  const std::string name = path_.string();
  root_.close_now();
  if (file_.get() < 0) return;
  if (!writable_) {
    if (!file_.reset()) fail("close file", name);
    return;
  }
  check_status(H5Fflush(file_.get(), H5F_SCOPE_LOCAL), "flush file", name);
  const ssize_t size = H5Fget_file_image(file_.get(), nullptr, 0);
  if (size < 0) fail("size the file image", name);
  const auto image = std::make_unique_for_overwrite<char[]>(static_cast<std::size_t>(size));
  if (H5Fget_file_image(file_.get(), image.get(), static_cast<std::size_t>(size)) != size) {
    fail("copy the file image", name);
  }
  if (!file_.reset()) fail("close file", name);
  write_whole_file(path_, std::span<const char>(image.get(), static_cast<std::size_t>(size)));
}

bool is_hdf5_file(const std::filesystem::path& path) {
  silence_error_printing();
  const std::string name = path.string();
  const htri_t result = H5Fis_hdf5(name.c_str());
  if (result < 0) H5Eclear2(H5E_DEFAULT);
  return result > 0;
}

}  // namespace scatterlab::hdf5
