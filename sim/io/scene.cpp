#include "scatterlab/io/scene.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <limits>
#include <vector>

#include "scatterlab/core/error.hpp"
#include "scatterlab/io/material_presets.hpp"
#include "scatterlab/io/toml_reader.hpp"
#include "scatterlab/transport/run_settings.hpp"

namespace scatterlab {
namespace {

using namespace toml_reading;

class SceneReader : public TomlReader {
 public:
  SceneReader(const std::string& origin, Validation validation)
      : TomlReader(origin), validation_(validation) {}

  Scene read(const toml::table& root) {
    check_keys(root, "", {"geometry", "medium", "source", "grid", "tallies", "run", "output"});
    Scene scene;
    SimulationSpec& spec = scene.spec;
    if (const auto* geometry = subtable(root, "geometry", "")) {
      check_keys(*geometry, "geometry", {"type"});
      read_geometry_type(
          *geometry, "infinite",
          "\"infinite\", \"sphere\", \"mesh\" or \"slab\" (a half-space scene runs with "
          "scatterlab searchlight)");
    }
    if (const auto* medium = subtable(root, "medium", "")) {
      scene.material = read_medium(*medium, spec.medium, spec.material, nullptr);
    }
    if (const auto* source = subtable(root, "source", "")) read_source(*source, spec.source);
    if (const auto* grid = subtable(root, "grid", "")) read_grid(*grid, spec.grid);
    spec.set_source(spec.source);  // the source's default tallies, unless [tallies] says else
    if (const auto* tallies = subtable(root, "tallies", "")) read_tallies(*tallies, spec.tallies);
    if (const auto* run = subtable(root, "run", "")) read_run(*run, spec.run);
    scene.output_path = read_output(root);
    if (validation_ == Validation::on_read) spec.validate();
    return scene;
  }

  // The searchlight's scene (scene.hpp): the same tables where they mean the same, plus
  // [geometry] eta (or [surface] eta) and [source] incidence_deg.
  SearchlightScene read_searchlight(const toml::table& root) {
    check_keys(root, "",
               {"geometry", "medium", "surface", "source", "grid", "tallies", "run", "output"});
    SearchlightScene scene;
    SearchlightSpec& spec = scene.spec;
    if (const auto* medium = subtable(root, "medium", "")) {
      scene.material = read_medium(*medium, spec.medium, spec.material, &spec.eta);
    }
    const std::string_view eta_accepted = "a finite number > 0";
    const toml::table* geometry = subtable(root, "geometry", "");
    if (geometry != nullptr) {
      check_keys(*geometry, "geometry", {"type", "eta"});
      read_geometry_type(*geometry, "half_space",
                         "\"half_space\" (an infinite-medium scene runs with scatterlab simulate)");
      if (const auto eta = number(*geometry, "eta", "geometry", eta_accepted)) {
        if (!(*eta > 0.0)) {
          throw InputError("geometry.eta", fmt::format("got {}", *eta) + at(*geometry->get("eta")),
                           std::string(eta_accepted));
        }
        spec.eta = *eta;
        scene.eta_given = true;
      }
    }
    if (const auto* surface = subtable(root, "surface", "")) {
      check_keys(*surface, "surface", {"eta"});
      if (const auto eta = number(*surface, "eta", "surface", eta_accepted)) {
        if (geometry != nullptr && geometry->get("eta") != nullptr) {
          throw InputError("surface.eta",
                           "given together with geometry.eta" + at(*surface->get("eta")),
                           "the index once: geometry.eta (or surface.eta, as older scenes say)");
        }
        spec.eta = *eta;
        scene.eta_given = true;
      }
    }
    if (const auto* source = subtable(root, "source", "")) {
      check_keys(*source, "source", {"incidence_deg"});
      const auto angle = number(*source, "incidence_deg", "source", "an angle in [0, 90) degrees");
      if (angle) spec.incidence_deg = *angle;
    }
    if (const auto* grid = subtable(root, "grid", "")) {
      check_keys(*grid, "grid", {"r", "z", "theta_o", "x", "y"});
      read_axis(*grid, "r", {"max", "bins"}, spec.grid.r);
      read_axis(*grid, "z", {"max", "bins"}, spec.grid.z);
      read_axis(*grid, "theta_o", {"bins"}, spec.grid.theta_o);
      read_axis(*grid, "x", {"min", "max", "bins"}, spec.grid.x);
      read_axis(*grid, "y", {"min", "max", "bins"}, spec.grid.y);
    }
    if (const auto* tallies = subtable(root, "tallies", "")) {
      check_keys(*tallies, "tallies", {"fluence", "exitance_map"});
      if (const auto on = boolean(*tallies, "fluence", "tallies")) spec.tallies.fluence = *on;
      if (const auto on = boolean(*tallies, "exitance_map", "tallies")) {
        spec.tallies.exitance_map = *on;
      }
    }
    if (const auto* run = subtable(root, "run", "")) read_run(*run, spec.run);
    scene.output_path = read_output(root);
    if (validation_ == Validation::on_read) spec.validate();
    return scene;
  }

  // The lit sphere's scene (scene.hpp): [geometry] type = "sphere", radius, eta; [source] type;
  // [grid] psi, azimuth; [tallies] split_by_order; the medium, run and output as above.
  LitSphereScene read_lit_sphere(const toml::table& root) {
    check_keys(root, "",
               {"geometry", "mesh", "medium", "source", "grid", "tallies", "run", "output"});
    LitSphereScene scene;
    LitSphereSpec& spec = scene.spec;
    if (const auto* medium = subtable(root, "medium", "")) {
      scene.material = read_medium(*medium, spec.medium, spec.material, &spec.eta);
    }
    if (const toml::table* geometry = subtable(root, "geometry", "")) {
      check_keys(*geometry, "geometry", {"type", "radius", "eta"});
      const std::string_view types = "\"sphere\" or \"mesh\" (with a [mesh] table)";
      const auto type = string(*geometry, "type", "geometry", types);
      if (type && *type != "sphere" && *type != "mesh") {
        wrong_type(*geometry->get("type"), "geometry.type", types);
      }
      scene.mesh = type == "mesh";
      if (scene.mesh && geometry->get("radius") != nullptr) {
        throw InputError("geometry.radius", "given for a mesh" + at(*geometry->get("radius")),
                         "the mesh's size in its [mesh] table");
      }
      if (const auto radius = number(*geometry, "radius", "geometry",
                                     "a finite number > 0 (in medium.length_unit)")) {
        spec.radius = *radius;
      }
      if (const auto eta = number(*geometry, "eta", "geometry", "a number in [0.1, 10]")) {
        spec.eta = *eta;
        scene.eta_given = true;
      }
    }
    if (const auto* source = subtable(root, "source", "")) {
      check_keys(*source, "source", {"type", "origin", "direction", "position", "radius"});
      const std::string_view accepted =
          "\"directional\", \"pole_beam\", \"beam\" or \"sphere\" (a sphere of light, on a "
          "mesh)";
      if (const auto type = string(*source, "type", "source", accepted)) {
        if (*type == "directional") {
          spec.light = SphereLight::directional;
        } else if (*type == "pole_beam") {
          spec.light = SphereLight::pole_beam;
        } else if (*type == "beam") {
          spec.light = SphereLight::beam;
        } else if (*type == "sphere") {
          spec.light = SphereLight::sphere;
        } else {
          wrong_type(*source->get("type"), "source.type", accepted);
        }
      }
      const std::string_view vector = "three numbers [x, y, z]";
      if (const auto origin = vector3(*source, "origin", "source", vector)) {
        spec.beam_origin = *origin;
      }
      if (const auto direction = vector3(*source, "direction", "source", vector)) {
        spec.beam_direction = *direction;
      }
      for (const char* key : {"origin", "direction"}) {
        if (source->get(key) != nullptr && spec.light != SphereLight::beam) {
          throw InputError(std::string("source.") + key,
                           "given for a light that is not a beam" + at(*source->get(key)),
                           "source.origin and source.direction with source.type = \"beam\"");
        }
      }
      if (const auto position = vector3(*source, "position", "source", vector)) {
        spec.light_center = *position;
      }
      if (const auto radius =
              number(*source, "radius", "source", "a finite number > 0 (in medium.length_unit)")) {
        spec.light_radius = *radius;
      }
      for (const char* key : {"position", "radius"}) {
        if (source->get(key) != nullptr && spec.light != SphereLight::sphere) {
          throw InputError(std::string("source.") + key,
                           "given for a light that is not a sphere" + at(*source->get(key)),
                           "source.position and source.radius with source.type = \"sphere\"");
        }
      }
    }
    if (root.get("mesh") != nullptr && !scene.mesh) {
      throw InputError("mesh", "given for a sphere" + at(*root.get("mesh")),
                       "a [mesh] table with geometry.type = \"mesh\"");
    }
    if (root.get("mesh") == nullptr && scene.mesh) {
      throw InputError("mesh", "missing", "a [mesh] table with geometry.type = \"mesh\"");
    }
    if (const auto* grid = subtable(root, "grid", "")) {
      if (scene.mesh) {
        throw InputError("grid", "given for a mesh" + at(*root.get("grid")),
                         "no [grid]: a mesh's exitance is per triangle");
      }
      check_keys(*grid, "grid", {"psi", "azimuth"});
      read_axis(*grid, "psi", {"bins"}, spec.psi);
      read_axis(*grid, "azimuth", {"bins"}, spec.azimuth);
    }
    if (const auto* tallies = subtable(root, "tallies", "")) {
      check_keys(*tallies, "tallies", {"split_by_order"});
      if (const auto on = boolean(*tallies, "split_by_order", "tallies")) spec.split_by_order = *on;
    }
    if (const auto* run = subtable(root, "run", "")) read_run(*run, spec.run);
    scene.output_path = read_output(root);
    if (validation_ == Validation::on_read && !scene.mesh) spec.validate();
    return scene;
  }

  // The layered slab's scene (scene.hpp): [geometry] with the ambient indices and the length
  // unit, an array [[layers]] top down, the grid, the tallies and the run with its weighting.
  LayeredSlabScene read_layered_slab(const toml::table& root) {
    check_keys(root, "", {"geometry", "layers", "grid", "tallies", "run", "output"});
    LayeredSlabScene scene;
    LayeredSlabSpec& spec = scene.spec;
    if (const toml::table* geometry = subtable(root, "geometry", "")) {
      check_keys(*geometry, "geometry", {"type", "length_unit", "n_above", "n_below"});
      read_geometry_type(*geometry, "slab", "\"slab\"");
      if (const auto unit = string(*geometry, "length_unit", "geometry",
                                   "one of \"mfp\", \"um\", \"mm\", \"cm\", \"m\"")) {
        spec.length_unit = *unit;
      }
      const std::string_view index = "a refractive index in [0.1, 10]";
      if (const auto n = number(*geometry, "n_above", "geometry", index)) spec.n_above = *n;
      if (const auto n = number(*geometry, "n_below", "geometry", index)) spec.n_below = *n;
    }
    const toml::node* layers = root.get("layers");
    const toml::array* list = layers != nullptr ? layers->as_array() : nullptr;
    const std::string_view layers_accepted =
        "an array of tables [[layers]], top down, each with mu_a, mu_s, g, n and thickness (or "
        "material and channel, and thickness)";
    if (layers == nullptr) throw InputError("layers", "missing", std::string(layers_accepted));
    if (list == nullptr || list->empty()) wrong_type(*layers, "layers", layers_accepted);
    spec.layers.clear();
    for (std::size_t i = 0; i < list->size(); ++i) {
      const toml::table* table = (*list)[i].as_table();
      if (table == nullptr) wrong_type((*list)[i], "layers", layers_accepted);
      spec.layers.push_back(read_layer(*table, fmt::format("layers[{}]", i + 1), spec));
    }
    if (const auto* grid = subtable(root, "grid", "")) {
      check_keys(*grid, "grid", {"r", "z", "theta_o"});
      read_axis(*grid, "r", {"max", "bins"}, spec.r);
      read_axis(*grid, "z", {"max", "bins"}, spec.z);
      read_axis(*grid, "theta_o", {"bins"}, spec.theta_o);
    }
    if (const auto* tallies = subtable(root, "tallies", "")) {
      check_keys(*tallies, "tallies", {"split_by_order"});
      if (const auto on = boolean(*tallies, "split_by_order", "tallies")) spec.split_by_order = *on;
    }
    if (const auto* run = subtable(root, "run", "")) read_run(*run, spec.run, &spec.weighting);
    scene.output_path = read_output(root);
    if (validation_ == Validation::on_read) spec.validate();
    return scene;
  }

 private:
  // One layer of the slab: its coefficients in the slab's length unit, or a measured material
  // (io/material_presets.hpp) converted to it, whose table's index is the layer's n unless given.
  SlabLayerSpec read_layer(const toml::table& table, const std::string& path,
                           const LayeredSlabSpec& spec) const {
    check_keys(table, path, {"mu_a", "mu_s", "g", "n", "thickness", "material", "channel"});
    SlabLayerSpec layer;
    const auto coefficient = [&](const char* key) {
      return number(table, key, path, "a finite number >= 0, in 1/geometry.length_unit");
    };
    const auto mu_a = coefficient("mu_a"), mu_s = coefficient("mu_s");
    const auto g = number(table, "g", path, "a number with |g| < 1");
    const auto n = number(table, "n", path, "a refractive index in [0.1, 10]");
    const auto thickness =
        number(table, "thickness", path, "a number > 0 (in geometry.length_unit), or inf");
    const auto material =
        string(table, "material", path, "a material name from data/materials, e.g. \"skin1\"");
    const auto channel =
        string(table, "channel", path, "a channel of the material's table, e.g. \"red\"");
    const auto require = [&](const auto& value, const char* key, const char* accepted) {
      if (!value) {
        throw InputError(dotted(path, key), "missing" + at(table.source()), accepted);
      }
    };
    require(thickness, "thickness", "a number > 0 (in geometry.length_unit), or inf");
    layer.thickness = *thickness;
    if (material) {
      for (const char* key : {"mu_a", "mu_s"}) {
        if (const toml::node* node = table.get(key)) {
          throw InputError(dotted(path, key), "given together with a material" + at(*node),
                           "either material (with channel, and optionally g and n) or the "
                           "layer's mu_a and mu_s");
        }
      }
      if (spec.length_unit == "mfp") {
        throw InputError(dotted(path, "material"), "given in a slab of length_unit \"mfp\"",
                         "a material in a slab of physical length_unit (\"mm\", \"cm\", ...)");
      }
      const ResolvedMaterial resolved =
          resolve_material({*material, channel, spec.length_unit, g},
                           {dotted(path, "material"), dotted(path, "channel"),
                            "geometry.length_unit", dotted(path, "g")});
      layer.mu_a = resolved.medium.sigma_a();
      layer.mu_s = resolved.medium.sigma_s();
      layer.g = resolved.medium.g;
      layer.n = n.value_or(resolved.eta);
      layer.material = resolved.origin;
      return layer;
    }
    if (channel) {
      throw InputError(dotted(path, "channel"),
                       "given without a material" + at(*table.get("channel")),
                       "channel only with a material");
    }
    require(mu_a, "mu_a", "a finite number >= 0, in 1/geometry.length_unit");
    require(mu_s, "mu_s", "a finite number >= 0, in 1/geometry.length_unit");
    require(g, "g", "a number with |g| < 1");
    require(n, "n", "a refractive index in [0.1, 10]");
    layer.mu_a = *mu_a;
    layer.mu_s = *mu_s;
    layer.g = *g;
    layer.n = *n;
    return layer;
  }

  // [geometry] type: each command runs one geometry; a scene for the other is named as such.
  void read_geometry_type(const toml::table& geometry, std::string_view expected,
                          std::string_view accepted) const {
    const auto type = string(geometry, "type", "geometry", accepted);
    if (type && *type != expected) wrong_type(*geometry.get("type"), "geometry.type", accepted);
  }

  Validation validation_;

  std::optional<std::string> read_output(const toml::table& root) const {
    const auto* output = subtable(root, "output", "");
    if (output == nullptr) return std::nullopt;
    check_keys(*output, "output", {"path"});
    auto path = string(*output, "path", "output", "a non-empty file name");
    if (path && path->empty()) {
      throw InputError("output.path", "is empty" + at(*output->get("path")),
                       "a non-empty file name");
    }
    return path;
  }

  // Either (albedo, sigma_t, g), (sigma_a, sigma_s, g) or a measured material (material, channel,
  // and optionally g and length_unit: io/material_presets.hpp), never a mix. A material also sets
  // *eta (the searchlight's index) when eta is given; the request is returned so that the
  // command's flags can re-resolve it.
  std::optional<MaterialRequest> read_medium(const toml::table& table, Medium& medium,
                                             std::optional<MaterialOrigin>& origin,
                                             double* eta) const {
    const std::string path = "medium";
    check_keys(
        table, path,
        {"albedo", "sigma_t", "g", "sigma_a", "sigma_s", "length_unit", "material", "channel"});
    const auto albedo = number(table, "albedo", path, "a number in [0, 1]");
    const auto sigma_t = number(table, "sigma_t", path, "a finite number > 0, in 1/length_unit");
    const auto g = number(table, "g", path, "a number with |g| < 1");
    const auto sigma_a = number(table, "sigma_a", path, "a finite number >= 0, in 1/length_unit");
    const auto sigma_s = number(table, "sigma_s", path, "a finite number >= 0, in 1/length_unit");
    const auto unit =
        string(table, "length_unit", path, "one of \"mfp\", \"um\", \"mm\", \"cm\", \"m\"");
    const auto material =
        string(table, "material", path, "a material name from data/materials, e.g. \"apple\"");
    const auto channel =
        string(table, "channel", path, "a channel of the material's table, e.g. \"red\"");

    if (material) {
      for (const char* key : {"albedo", "sigma_t", "sigma_a", "sigma_s"}) {
        if (const toml::node* node = table.get(key)) {
          throw InputError(dotted(path, key), "given together with medium.material" + at(*node),
                           "either medium.material (with channel, and optionally g and "
                           "length_unit) or the medium's coefficients");
        }
      }
      MaterialRequest request{*material, channel, unit, g};
      ResolvedMaterial resolved = resolve_material(
          request, {"medium.material", "medium.channel", "medium.length_unit", "medium.g"});
      medium = resolved.medium;
      origin = resolved.origin;
      if (eta != nullptr) *eta = resolved.eta;
      return request;
    }
    if (channel) {
      throw InputError("medium.channel",
                       "given without medium.material" + at(*table.get("channel")),
                       "channel only with a material (medium.material = \"apple\", say)");
    }
    if (!sigma_a && !sigma_s) {
      if (albedo) medium.albedo = *albedo;
      if (sigma_t) medium.sigma_t = *sigma_t;
      if (g) medium.g = *g;
      medium.length_unit = unit.value_or("mfp");
      return std::nullopt;
    }
    const std::string_view accepted =
        "either albedo, sigma_t, g or sigma_a, sigma_s, g (with length_unit)";
    if (albedo || sigma_t) {
      const std::string_view mixed = albedo ? "albedo" : "sigma_t";
      throw InputError(
          dotted(path, mixed),
          "given together with medium.sigma_a / medium.sigma_s" + at(*table.get(mixed)),
          std::string(accepted));
    }
    if (!sigma_a || !sigma_s) {
      throw InputError(sigma_a ? "medium.sigma_s" : "medium.sigma_a",
                       sigma_a ? "missing while medium.sigma_a is given"
                               : "missing while medium.sigma_s is given",
                       "both sigma_a and sigma_s, in 1/length_unit");
    }
    medium =
        Medium::from_coefficients(*sigma_a, *sigma_s, g.value_or(medium.g), unit.value_or("mm"));
    return std::nullopt;
  }

  void read_source(const toml::table& table, SourceKind& source) const {
    check_keys(table, "source", {"type"});
    const std::string_view accepted = "\"beam\" or \"point\"";
    const auto type = string(table, "type", "source", accepted);
    if (!type) return;
    if (*type == "beam") {
      source = SourceKind::pencil_beam;
    } else if (*type == "point") {
      source = SourceKind::point;
    } else {
      wrong_type(*table.get("type"), "source.type", accepted);
    }
  }

  void read_axis(const toml::table& grid, std::string_view name, Keys keys,
                 UniformAxis& axis) const {
    const toml::table* table = subtable(grid, name, "grid");
    if (table == nullptr) return;
    const std::string path = dotted("grid", name);
    check_keys(*table, path, keys);
    if (const auto min = number(*table, "min", path, "a finite number (in medium.length_unit)"))
      axis.min = *min;
    if (const auto max = number(*table, "max", path, "a finite number (in medium.length_unit)"))
      axis.max = *max;
    if (const auto bins = integer_as<int>(*table, "bins", path, 1, "an integer in [1, 100000]")) {
      axis.bins = *bins;
    }
  }

  void read_grid(const toml::table& table, Grid& grid) const {
    check_keys(table, "grid", {"r", "z", "theta", "phi", "fold_phi", "rho"});
    read_axis(table, "r", {"max", "bins"}, grid.r);
    read_axis(table, "z", {"min", "max", "bins"}, grid.z);
    read_axis(table, "theta", {"bins"}, grid.theta);
    read_axis(table, "phi", {"bins"}, grid.phi);
    read_axis(table, "rho", {"max", "bins"}, grid.rho);
    if (const auto fold = boolean(table, "fold_phi", "grid")) {
      grid.set_fold_phi(*fold);
    }
  }

  void read_tallies(const toml::table& table, TallyRequest& tallies) const {
    const std::string path = "tallies";
    check_keys(table, path,
               {"radiance", "fluence", "flux", "fluence_spherical", "split_by_order", "estimator"});
    if (const auto on = boolean(table, "radiance", path)) tallies.radiance = *on;
    if (const auto on = boolean(table, "fluence", path)) tallies.fluence = *on;
    if (const auto on = boolean(table, "flux", path)) tallies.flux = *on;
    if (const auto on = boolean(table, "fluence_spherical", path)) tallies.fluence_spherical = *on;
    if (const auto on = boolean(table, "split_by_order", path)) tallies.split_by_order = *on;
    const std::string_view accepted = "\"collision\" or \"track_length\"";
    if (const auto estimator = string(table, "estimator", path, accepted)) {
      if (*estimator == "collision") {
        tallies.estimator = Estimator::collision;
      } else if (*estimator == "track_length") {
        tallies.estimator = Estimator::track_length;
      } else {
        wrong_type(*table.get("estimator"), "tallies.estimator", accepted);
      }
    }
  }

  // `weighting`: where the scene's run may choose it (a slab), else null and refused.
  void read_run(const toml::table& table, RunSettings& run, Weighting* weighting = nullptr) const {
    const std::string path = "run";
    if (weighting != nullptr) {
      check_keys(table, path,
                 {"photons", "batches", "seed", "threads", "escape_radius", "weighting"});
      const std::string_view accepted = "\"analog\" or \"implicit\"";
      if (const auto w = string(table, "weighting", path, accepted)) {
        if (*w == "analog") {
          *weighting = Weighting::analog;
        } else if (*w == "implicit") {
          *weighting = Weighting::implicit_capture;
        } else {
          wrong_type(*table.get("weighting"), "run.weighting", accepted);
        }
      }
    } else {
      check_keys(table, path, {"photons", "batches", "seed", "threads", "escape_radius"});
    }
    if (const auto photons =
            integer_as<std::uint64_t>(table, "photons", path, 0, "an integer >= 1")) {
      run.photons = *photons;
    }
    if (const auto batches = integer_as<std::uint32_t>(table, "batches", path, 0,
                                                       "an integer in [2, run.photons]")) {
      run.batches = *batches;
    }
    // Seed and threads are held to their bounds by check_run_settings, after the flags are
    // applied, with the same check as --seed and --threads (run_settings.hpp).
    if (const auto seed = integer_as<std::uint64_t>(table, "seed", path, 0, seed_accepted)) {
      run.seed = *seed;
    }
    if (const auto threads = integer_as<int>(table, "threads", path, 0, threads_accepted())) {
      run.threads = *threads;
    }
    if (const auto radius =
            number(table, "escape_radius", path, "a number > 0 (in medium.length_unit), or inf")) {
      run.escape_radius = *radius;
    }
  }
};

// A key of the scene that holds a list of values to sweep over.
struct SweptKey {
  std::vector<std::string> path;  // tables down to the key, then the key
  const toml::array* values;
};

std::string join_path(const std::vector<std::string>& path) {
  std::string joined;
  for (const std::string& part : path) {
    if (!joined.empty()) joined += '.';
    joined += part;
  }
  return joined;
}

// Every array in the document, in file order (toml++ keeps insertion order).
void find_lists(const toml::table& table, std::vector<std::string>& path,
                std::vector<SweptKey>& found, const std::string& origin) {
  for (auto&& [key, node] : table) {
    path.emplace_back(key.str());
    if (const auto* sub = node.as_table()) {
      find_lists(*sub, path, found, origin);
    } else if (const auto* list = node.as_array()) {
      const auto& begin = node.source().begin;
      const std::string where = fmt::format(" ({}:{}:{})", origin, begin.line, begin.column);
      if (list->empty()) {
        throw InputError(join_path(path), "is an empty list" + where,
                         "a value, or a non-empty list of values to sweep over");
      }
      for (const toml::node& value : *list) {
        if (value.is_array() || value.is_table()) {
          throw InputError(join_path(path), "is a list holding a list or table" + where,
                           "a value, or a list of plain values to sweep over");
        }
      }
      found.push_back({path, list});
    }
    path.pop_back();
  }
}

std::string value_label(const toml::node& node) {
  if (const auto* v = node.as_floating_point()) return fmt::format("{}", v->get());
  if (const auto* v = node.as_integer()) return fmt::format("{}", v->get());
  if (const auto* v = node.as_boolean()) return v->get() ? "true" : "false";
  if (const auto* v = node.as_string()) return v->get();
  return "value";
}

// "albedo" unless another swept key also ends in "albedo"; then the dotted path.
std::string key_label(const std::vector<SweptKey>& swept, std::size_t index) {
  const std::string& last = swept[index].path.back();
  for (std::size_t j = 0; j < swept.size(); ++j) {
    if (j != index && swept[j].path.back() == last) return join_path(swept[index].path);
  }
  return last;
}

// The table of `document` that holds `key` (find_lists found it there, so every table exists).
toml::table& holder(toml::table& document, const SweptKey& key) {
  toml::table* table = &document;
  for (std::size_t depth = 0; depth + 1 < key.path.size(); ++depth) {
    table = table->get(key.path[depth])->as_table();
  }
  return *table;
}

// From the lengths of the lists, before any point is made.
void check_sweep_size(const std::vector<SweptKey>& swept, const std::string& origin) {
  double points = 1.0;
  std::string keys, lengths;
  for (const SweptKey& key : swept) {
    points *= static_cast<double>(key.values->size());
    keys += (keys.empty() ? "" : " x ") + join_path(key.path);
    lengths += (lengths.empty() ? "" : " x ") + std::to_string(key.values->size());
  }
  if (points <= static_cast<double>(max_sweep_points)) return;
  throw InputError(
      keys, fmt::format("the lists make {} = {:.0f} combinations ({})", lengths, points, origin),
      fmt::format("at most {} combinations in one sweep file (one run and one file "
                  "each): split the study into several files",
                  max_sweep_points));
}

}  // namespace

Scene parse_scene(std::string_view toml_text, const std::string& origin, Validation validation) {
  return SceneReader(origin, validation).read(parse_toml(toml_text, origin));
}

Scene load_scene(const std::filesystem::path& path, Validation validation) {
  return parse_scene(read_text(path), path.string(), validation);
}

std::vector<SweepPoint> parse_sweep(std::string_view toml_text, const std::string& origin,
                                    Validation validation) {
  const toml::table root = parse_toml(toml_text, origin);
  std::vector<SweptKey> swept;
  std::vector<std::string> path;
  find_lists(root, path, swept, origin);
  check_sweep_size(swept, origin);
  // Each point copies the scene with one value in place of each list, not the lists themselves,
  // so that a sweep costs its points times the size of one scene.
  toml::table scene = root;
  for (const SweptKey& key : swept) holder(scene, key).insert_or_assign(key.path.back(), 0);
  std::vector<SweepPoint> points;
  // Odometer over the lists, the last fastest.
  std::vector<std::size_t> index(swept.size(), 0);
  while (true) {
    toml::table point = scene;
    std::string label;
    for (std::size_t k = 0; k < swept.size(); ++k) {
      const toml::node& value = *swept[k].values->get(index[k]);
      holder(point, swept[k]).insert_or_assign(swept[k].path.back(), value);
      label +=
          fmt::format("{}{}={}", label.empty() ? "" : "_", key_label(swept, k), value_label(value));
    }
    points.push_back({label, SceneReader(origin, validation).read(point)});
    std::size_t k = swept.size();
    while (k > 0 && ++index[k - 1] == swept[k - 1].values->size()) index[--k] = 0;
    if (k == 0) break;
  }
  return points;
}

std::vector<SweepPoint> load_sweep(const std::filesystem::path& path, Validation validation) {
  return parse_sweep(read_text(path), path.string(), validation);
}

SearchlightScene parse_searchlight_scene(std::string_view toml_text, const std::string& origin,
                                         Validation validation) {
  return SceneReader(origin, validation).read_searchlight(parse_toml(toml_text, origin));
}

SearchlightScene load_searchlight_scene(const std::filesystem::path& path, Validation validation) {
  return parse_searchlight_scene(read_text(path), path.string(), validation);
}

LitSphereScene parse_lit_sphere_scene(std::string_view toml_text, const std::string& origin,
                                      Validation validation) {
  return SceneReader(origin, validation).read_lit_sphere(parse_toml(toml_text, origin));
}

LitSphereScene load_lit_sphere_scene(const std::filesystem::path& path, Validation validation) {
  return parse_lit_sphere_scene(read_text(path), path.string(), validation);
}

LayeredSlabScene parse_layered_slab_scene(std::string_view toml_text, const std::string& origin,
                                          Validation validation) {
  return SceneReader(origin, validation).read_layered_slab(parse_toml(toml_text, origin));
}

LayeredSlabScene load_layered_slab_scene(const std::filesystem::path& path, Validation validation) {
  return parse_layered_slab_scene(read_text(path), path.string(), validation);
}

std::string scene_geometry(const std::filesystem::path& path) {
  const toml::table root = parse_toml(read_text(path), path.string());
  if (const toml::table* geometry = root["geometry"].as_table()) {
    if (const auto type = (*geometry)["type"].value<std::string>()) return *type;
  }
  return "infinite";
}

}  // namespace scatterlab
