#include "dimension_scales.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>

namespace scatterlab {
namespace {

// The scale of dimension `name` (n bins) in `group`: bin centres of the group's own axis
// (axes/<name>, a declared tally's) or of /grid/<name>, or indices.
hdf5::Dataset write_scale(const hdf5::Group& root, hdf5::Group& group, const std::string& name,
                          std::size_t n) {
  const bool owned = group.has_member("axes") && group.open_group("axes").has_member(name);
  const std::string axis = owned ? "axes/" + name : "grid/" + name;
  const hdf5::Group& holder = owned ? group : root;
  if (holder.has_member(axis)) {
    const hdf5::Dataset edges_dataset = holder.open_dataset(axis);
    const hdf5::Array edges = edges_dataset.read();
    bool finite = edges.values.size() == n + 1;
    for (const double edge : edges.values) finite = finite && std::isfinite(edge);
    if (finite) {
      std::vector<double> centres(n);
      for (std::size_t i = 0; i < n; ++i)
        centres[i] = 0.5 * (edges.values[i] + edges.values[i + 1]);
      hdf5::Dataset scale = group.write_dataset(name, centres);
      scale.write_string_attribute("units", edges_dataset.read_string_attribute("units"));
      scale.write_string_attribute(
          "description", fmt::format("bin centres of {}; the edges are {}", name,
                                     owned ? group.path_in_file() + "/" + axis : "/" + axis));
      scale.make_dimension_scale(name);
      return scale;
    }
  }
  std::vector<std::int32_t> index(n);
  for (std::size_t i = 0; i < n; ++i) index[i] = static_cast<std::int32_t>(i);
  hdf5::Dataset scale = group.write_dataset(name, index, {n});
  scale.write_string_attribute("units", "1");
  scale.write_string_attribute("description", fmt::format("bin index along {}", name));
  scale.make_dimension_scale(name);
  return scale;
}

// Attaches a scale to each dimension of `group`/`data` named in `dims`.
void label_dimensions(const hdf5::Group& root, hdf5::Group& group, const std::string& data_name,
                      const std::string& dims) {
  const std::vector<std::string> names = split_dims(dims);
  if (names.empty()) return;
  hdf5::Dataset data = group.open_dataset(data_name);
  const std::vector<std::size_t> shape = data.shape();
  if (names.size() != shape.size()) {
    throw std::runtime_error(
        fmt::format("{}: dims '{}' do not match its rank {}", data.location(), dims, shape.size()));
  }
  for (std::size_t d = 0; d < names.size(); ++d) {
    const hdf5::Dataset scale = group.has_member(names[d])
                                    ? group.open_dataset(names[d])
                                    : write_scale(root, group, names[d], shape[d]);
    scale.attach_dimension_scale(data, static_cast<unsigned>(d), names[d]);
  }
}

}  // namespace

std::vector<std::string> split_dims(const std::string& dims) {
  std::vector<std::string> names;
  if (dims.empty()) return names;
  std::size_t start = 0;
  for (std::size_t comma = dims.find(','); comma != std::string::npos;
       comma = dims.find(',', start)) {
    names.push_back(dims.substr(start, comma - start));
    start = comma + 1;
  }
  names.push_back(dims.substr(start));
  return names;
}

void write_dimension_scales(hdf5::Group& root) {
  if (root.has_member("tallies")) {
    hdf5::Group tallies = root.open_group("tallies");
    for (const std::string& name : tallies.member_names()) {
      hdf5::Group tally = tallies.open_group(name);
      const std::string dims = tally.read_string_attribute("dims");
      for (const char* data : {"mean", "stderr"}) label_dimensions(root, tally, data, dims);
    }
  }
  if (root.has_member("models")) {
    hdf5::Group models = root.open_group("models");
    for (const std::string& name : models.member_names()) {
      hdf5::Group model = models.open_group(name);
      for (const std::string& curve : curve_names(model)) {
        const hdf5::Dataset dataset = model.open_dataset(curve);
        if (!dataset.has_attribute("dims")) continue;
        label_dimensions(root, model, curve, dataset.read_string_attribute("dims"));
      }
    }
  }
}

std::vector<std::string> curve_names(const hdf5::Group& model) {
  std::vector<std::string> curves;
  for (const std::string& name : model.member_names()) {
    if (!model.open_dataset(name).is_dimension_scale()) curves.push_back(name);
  }
  return curves;
}

bool is_dimension_scale_attribute(std::string_view name) {
  constexpr std::array<std::string_view, 5> reserved = {"CLASS", "NAME", "REFERENCE_LIST",
                                                        "DIMENSION_LIST", "DIMENSION_LABELS"};
  for (const std::string_view r : reserved) {
    if (name == r) return true;
  }
  return false;
}

}  // namespace scatterlab
