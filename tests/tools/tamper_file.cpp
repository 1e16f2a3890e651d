// Usage: tamper_file FILE.h5 attribute GROUP NAME int|double|string VALUE
//        tamper_file FILE.h5 element GROUP DATASET INDEX VALUE|drop
// Changes one attribute, or one element of a double dataset (keeping its shape and attributes;
// "drop" removes the element of a 1-D dataset instead, which is then one shorter),
// of an HDF5 file in place (a rewritten dataset loses its dimension scales). Tests use it to make
// damaged inputs from real outputs: a NaN tally, a count that disagrees with another, an unknown
// format version. GROUP is "/" for the root.
#include <fmt/format.h>

#include <cstddef>
#include <cstdint>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/dimension_scales.hpp"
#include "scatterlab/io/hdf5_file.hpp"

namespace {

using scatterlab::hdf5::AttributeType;
using scatterlab::hdf5::Group;
using scatterlab::hdf5::Object;

void set_attribute(Object& object, const std::string& name, const std::string& type,
                   const std::string& value) {
  if (type == "int") return object.write_int64_attribute(name, std::stoll(value));
  if (type == "double") return object.write_double_attribute(name, std::stod(value));
  if (type == "string") return object.write_string_attribute(name, value);
  throw std::invalid_argument("type must be int, double or string, not " + type);
}

// Rewrites the dataset with one element changed; its attributes are carried over (numbers as
// doubles).
void set_element(Group& group, const std::string& name, std::size_t index,
                 const std::string& value) {
  const scatterlab::hdf5::Dataset old = group.open_dataset(name);
  scatterlab::hdf5::Array array = old.read();
  if (value == "drop") {
    if (array.shape.size() != 1) throw std::invalid_argument("drop needs a 1-D dataset");
    array.values.erase(array.values.begin() + static_cast<std::ptrdiff_t>(index));
    array.shape[0] -= 1;
  } else {
    array.values.at(index) = std::stod(value);
  }
  struct Saved {
    std::string name;
    AttributeType type;
    std::string text;
    double number;
  };
  std::vector<Saved> saved;
  for (const std::string& attribute : old.attribute_names()) {
    if (scatterlab::is_dimension_scale_attribute(attribute)) continue;  // references: not kept
    const AttributeType type = old.attribute_type(attribute);
    saved.push_back({attribute, type,
                     type == AttributeType::string ? old.read_string_attribute(attribute) : "",
                     type == AttributeType::string ? 0.0 : old.read_double_attribute(attribute)});
  }
  group.remove_member(name);
  scatterlab::hdf5::Dataset fresh = group.write_dataset(name, array.values, array.shape);
  for (const Saved& s : saved) {
    if (s.type == AttributeType::string) {
      fresh.write_string_attribute(s.name, s.text);
    } else {
      fresh.write_double_attribute(s.name, s.number);
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  const std::string what = argc > 2 ? argv[2] : "";
  if (!((what == "attribute" && argc == 7) || (what == "element" && argc == 7))) {
    fmt::print(stderr,
               "usage: tamper_file FILE.h5 attribute GROUP NAME int|double|string VALUE\n"
               "       tamper_file FILE.h5 element GROUP DATASET INDEX VALUE|drop\n");
    return 2;
  }
  try {
    auto file = scatterlab::hdf5::File::open_read_write(argv[1]);
    const auto change = [&](Group& group) {
      if (what == "attribute") {
        set_attribute(group, argv[4], argv[5], argv[6]);
      } else {
        set_element(group, argv[4], std::stoull(argv[5]), argv[6]);
      }
    };
    const std::string path = argv[3];
    if (path == "/") {
      change(file.root());
    } else {
      Group group = file.root().open_group(path);
      change(group);
    }
    file.close();
  } catch (const std::exception& failure) {
    fmt::print(stderr, "tamper_file: {}\n", failure.what());
    return 1;
  }
  return 0;
}
