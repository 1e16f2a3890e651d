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
#include <optional>
#include <span>
#include <sstream>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "scatterlab/core/error.hpp"
#include "scatterlab/io/material_presets.hpp"
#include "scatterlab/io/scene_schema.hpp"
#include "scatterlab/io/toml_reader.hpp"
#include "scatterlab/transport/run_settings.hpp"

namespace scatterlab {
namespace {

using namespace toml_reading;

class SceneReader : public TomlReader {
 public:
  SceneReader(const std::string& origin, Validation validation)
      : TomlReader(origin), validation_(validation) {}

  // The geometry.type the file names (default_geometry when none), then that geometry's tables.
  Scene read(const toml::table& root, std::string_view default_geometry) {
    std::string_view geometry = default_geometry;
    std::optional<std::string> type;
    if (const auto* table = subtable(root, "geometry", "")) {
      type = string(*table, "type", "geometry", geometries_accepted());
      if (type) {
        if (std::find(scene_geometries.begin(), scene_geometries.end(), *type) ==
            scene_geometries.end()) {
          wrong_type(*table->get("type"), "geometry.type", geometries_accepted());
        }
        geometry = *type;
      }
    }
    // One of scene_geometries (a string of the file's only as long as `root`).
    geometry_ = *std::find(scene_geometries.begin(), scene_geometries.end(), geometry);
    Scene scene;
    if (geometry == "half_space") {
      scene.spec = read_half_space(root, scene);
    } else if (geometry == "sphere" || geometry == "mesh") {
      scene.spec = read_lit_object(root, scene, geometry == "mesh");
    } else if (geometry == "slab") {
      scene.spec = read_layered_slab(root, scene);
    } else {
      scene.spec = read_infinite(root, scene);
    }
    std::visit([&](auto& spec) { spec.declared_tallies = read_declared_tallies(root); },
               scene.spec);
    // A mesh's spec is validated by the caller, once it holds the mesh.
    if (validation_ == Validation::on_read && geometry != "mesh") {
      std::visit([](const auto& spec) { spec.validate(); }, scene.spec);
    }
    return scene;
  }

 private:
  // The geometry.type values, as a refusal lists them.
  static const std::string& geometries_accepted() {
    static const std::string accepted = join(scene_geometries, "\"", "\"") +
                                        " (\"mesh\" with a [mesh] table, \"slab\" with [[layers]])";
    return accepted;
  }

  // The infinite medium (scene.hpp): [medium], [source] type, [grid], [tallies], [run], [output].
  InfiniteMediumSpec read_infinite(const toml::table& root, Scene& scene) const {
    check_table(root, "");
    InfiniteMediumSpec spec;
    if (const auto* geometry = subtable(root, "geometry", "")) {
      check_table(*geometry, "geometry");
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
    return spec;
  }

  // The searchlight's scene (scene.hpp): the same tables where they mean the same, plus
  // [geometry] eta (or [surface] eta) and [source] incidence_deg.
  HalfSpaceSpec read_half_space(const toml::table& root, Scene& scene) const {
    check_table(root, "");
    HalfSpaceSpec spec;
    if (const auto* medium = subtable(root, "medium", "")) {
      scene.material = read_medium(*medium, spec.medium, spec.material, &spec.eta);
    }
    const std::string_view eta_accepted = "a finite number > 0";
    const toml::table* geometry = subtable(root, "geometry", "");
    if (geometry != nullptr) {
      check_table(*geometry, "geometry");
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
      check_table(*surface, "surface");
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
      check_table(*source, "source");
      const auto angle = number(*source, "incidence_deg", "source", "an angle in [0, 90) degrees");
      if (angle) spec.incidence_deg = *angle;
    }
    if (const auto* grid = subtable(root, "grid", "")) {
      check_table(*grid, "grid");
      read_axis(*grid, "r", spec.grid.r);
      read_axis(*grid, "z", spec.grid.z);
      read_axis(*grid, "theta_o", spec.grid.theta_o);
      read_axis(*grid, "x", spec.grid.x);
      read_axis(*grid, "y", spec.grid.y);
    }
    if (const auto* tallies = subtable(root, "tallies", "")) {
      check_table(*tallies, "tallies");
      if (const auto on = boolean(*tallies, "fluence", "tallies")) spec.tallies.fluence = *on;
      if (const auto on = boolean(*tallies, "exitance_map", "tallies")) {
        spec.tallies.exitance_map = *on;
      }
    }
    if (const auto* run = subtable(root, "run", "")) read_run(*run, spec.run);
    scene.output_path = read_output(root);
    return spec;
  }

  // The lit sphere's scene (scene.hpp): [geometry] type = "sphere", radius, eta; [source] type;
  // [grid] psi, azimuth; [tallies] split_by_order; the medium, run and output as above.
  LitObjectSpec read_lit_object(const toml::table& root, Scene& scene, bool mesh) const {
    check_table(root, "");
    LitObjectSpec spec;
    if (const auto* medium = subtable(root, "medium", "")) {
      scene.material = read_medium(*medium, spec.medium, spec.material, &spec.eta);
    }
    if (const toml::table* geometry = subtable(root, "geometry", "")) {
      check_table(*geometry, "geometry");
      if (mesh && geometry->get("radius") != nullptr) {
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
      check_table(*source, "source");
      const std::string_view accepted =
          "\"directional\", \"pole_beam\", \"beam\" or \"sphere\" (a sphere of light, on a "
          "mesh)";
      if (const auto type = string(*source, "type", "source", accepted)) {
        if (*type == "directional") {
          spec.light = ObjectLight::directional;
        } else if (*type == "pole_beam") {
          spec.light = ObjectLight::pole_beam;
        } else if (*type == "beam") {
          spec.light = ObjectLight::beam;
        } else if (*type == "sphere") {
          spec.light = ObjectLight::sphere;
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
        if (source->get(key) != nullptr && spec.light != ObjectLight::beam) {
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
        if (source->get(key) != nullptr && spec.light != ObjectLight::sphere) {
          throw InputError(std::string("source.") + key,
                           "given for a light that is not a sphere" + at(*source->get(key)),
                           "source.position and source.radius with source.type = \"sphere\"");
        }
      }
    }
    if (root.get("mesh") != nullptr && !mesh) {
      throw InputError("mesh", "given for a sphere" + at(*root.get("mesh")),
                       "a [mesh] table with geometry.type = \"mesh\"");
    }
    if (root.get("mesh") == nullptr && mesh) {
      throw InputError("mesh", "missing", "a [mesh] table with geometry.type = \"mesh\"");
    }
    if (const auto* grid = subtable(root, "grid", "")) {
      if (mesh) {
        throw InputError("grid", "given for a mesh" + at(*root.get("grid")),
                         "no [grid]: a mesh's exitance is per triangle");
      }
      check_table(*grid, "grid");
      read_axis(*grid, "psi", spec.psi);
      read_axis(*grid, "azimuth", spec.azimuth);
    }
    if (const auto* tallies = subtable(root, "tallies", "")) {
      check_table(*tallies, "tallies");
      if (const auto on = boolean(*tallies, "split_by_order", "tallies")) spec.split_by_order = *on;
    }
    if (const auto* run = subtable(root, "run", "")) read_run(*run, spec.run);
    scene.output_path = read_output(root);
    return spec;
  }

  // The layered slab's scene (scene.hpp): [geometry] with the ambient indices and the length
  // unit, an array [[layers]] top down, the grid, the tallies and the run with its weighting.
  LayeredSlabSpec read_layered_slab(const toml::table& root, Scene& scene) const {
    check_table(root, "");
    LayeredSlabSpec spec;
    if (const toml::table* geometry = subtable(root, "geometry", "")) {
      check_table(*geometry, "geometry");
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
      check_table(*grid, "grid");
      read_axis(*grid, "r", spec.r);
      read_axis(*grid, "z", spec.z);
      read_axis(*grid, "theta_o", spec.theta_o);
    }
    if (const auto* tallies = subtable(root, "tallies", "")) {
      check_table(*tallies, "tallies");
      if (const auto on = boolean(*tallies, "split_by_order", "tallies")) spec.split_by_order = *on;
    }
    if (const auto* run = subtable(root, "run", "")) read_run(*run, spec.run, &spec.weighting);
    scene.output_path = read_output(root);
    return spec;
  }

  // One layer of the slab: its coefficients in the slab's length unit, or a measured material
  // (io/material_presets.hpp) converted to it, whose table's index is the layer's n unless given.
  SlabLayerSpec read_layer(const toml::table& table, const std::string& path,
                           const LayeredSlabSpec& spec) const {
    check_table(table, path);
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

  // A table's keys, checked against the schema's for this geometry (io/scene_schema.hpp); a
  // layer's ("layers[2]") are those of every layer, a tally's those of every tally.
  void check_table(const toml::table& table, const std::string& path) const {
    std::string schema_path = path;  // "tally[2].filters" is "tally.filters" in the schema
    for (std::size_t open = schema_path.find('['); open != std::string::npos;
         open = schema_path.find('[', open)) {
      schema_path.erase(open, schema_path.find(']', open) + 1 - open);
    }
    check_names(table, path, scene_table_keys(geometry_, schema_path));
  }

  Validation validation_;
  std::string_view geometry_ = "infinite";

  std::optional<std::string> read_output(const toml::table& root) const {
    const auto* output = subtable(root, "output", "");
    if (output == nullptr) return std::nullopt;
    check_table(*output, "output");
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
    check_table(table, path);
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
    check_table(table, "source");
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

  void read_axis(const toml::table& grid, std::string_view name, UniformAxis& axis) const {
    const toml::table* table = subtable(grid, name, "grid");
    if (table == nullptr) return;
    const std::string path = dotted("grid", name);
    check_table(*table, path);
    if (const auto min = number(*table, "min", path, "a finite number (in medium.length_unit)"))
      axis.min = *min;
    if (const auto max = number(*table, "max", path, "a finite number (in medium.length_unit)"))
      axis.max = *max;
    if (const auto bins = integer_as<int>(*table, "bins", path, 1, "an integer in [1, 100000]")) {
      axis.bins = *bins;
    }
  }

  // [[tally]]: the tallies a scene declares (transport/declared_tally.hpp), each with a name, a
  // score, an optional group_index and filters = { r = {...}, z = {...}, t = {...} }.
  std::vector<DeclaredTally> read_declared_tallies(const toml::table& root) const {
    std::vector<DeclaredTally> tallies;
    const toml::node* node = root.get("tally");
    if (node == nullptr) return tallies;
    const std::string_view accepted =
        "an array of tables [[tally]], each with name, score and filters";
    const toml::array* list = node->as_array();
    if (list == nullptr || list->empty()) wrong_type(*node, "tally", accepted);
    for (std::size_t i = 0; i < list->size(); ++i) {
      const toml::table* table = (*list)[i].as_table();
      if (table == nullptr) wrong_type((*list)[i], "tally", accepted);
      const std::string path = fmt::format("tally[{}]", i + 1);
      check_table(*table, path);
      DeclaredTally tally;
      const auto require = [&](std::string_view key, std::string_view what) {
        throw InputError(dotted(path, key), "is missing", std::string(what));
      };
      const std::string_view names = "1 to 64 letters, digits and _";
      if (const auto name = string(*table, "name", path, names)) {
        tally.name = *name;
      } else {
        require("name", names);
      }
      const std::string_view scores =
          "\"exitance\", \"transmittance\", \"fluence\", \"absorbed\", \"collisions\" or "
          "\"path_length\"";
      if (const auto score = string(*table, "score", path, scores)) {
        const std::optional<Score> known = declared_score(*score);
        if (!known) wrong_type(*table->get("score"), dotted(path, "score"), scores);
        tally.score = *known;
      } else {
        require("score", scores);
      }
      tally.group_index = number(*table, "group_index", path, "a refractive index in [0.1, 10]");
      if (const toml::table* filters = subtable(*table, "filters", path)) {
        const std::string at_filters = dotted(path, "filters");
        check_table(*filters, at_filters);
        for (const DeclaredFilterKey& declared : declared_filter_schema()) {
          const std::string_view name = declared.key;
          if (declared.axis == FilterAxis::each) {  // no axis: a bin per layer or triangle
            if (boolean(*filters, name, at_filters).value_or(false)) {
              tally.filters.push_back({*declared_filter(name), {}, {}, 0});
            }
          } else if (const toml::table* filter = subtable(*filters, name, at_filters)) {
            tally.filters.push_back(read_filter(*filter, dotted(at_filters, name), name));
          }
        }
      }
      tallies.push_back(std::move(tally));
    }
    return tallies;
  }

  // A declared tally's filter, as written: its keys are the schema's (theta_o and order take
  // bins alone); check_declared_tallies fills in its defaults and refuses what is missing.
  DeclaredFilter read_filter(const toml::table& table, const std::string& path,
                             std::string_view name) const {
    check_table(table, path);
    const std::string_view unit =
        name == "t" ? "a finite number, in seconds" : "a finite number, in the scene's length unit";
    DeclaredFilter filter;
    filter.coordinate = *declared_filter(name);
    filter.min = number(table, "min", path, unit);
    filter.max = number(table, "max", path, unit);
    filter.bins = integer_as<int>(table, "bins", path, 1, "an integer in [1, 100000]").value_or(0);
    return filter;
  }

  void read_grid(const toml::table& table, Grid& grid) const {
    check_table(table, "grid");
    read_axis(table, "r", grid.r);
    read_axis(table, "z", grid.z);
    read_axis(table, "theta", grid.theta);
    read_axis(table, "phi", grid.phi);
    read_axis(table, "rho", grid.rho);
    if (const auto fold = boolean(table, "fold_phi", "grid")) {
      grid.set_fold_phi(*fold);
    }
  }

  void read_tallies(const toml::table& table, TallyRequest& tallies) const {
    const std::string path = "tallies";
    check_table(table, path);
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
    check_table(table, path);
    if (weighting != nullptr) {
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

// Whether the key at `path` ("source.origin") takes a list of numbers, [x, y, z], as its one
// value (the schema's vector keys): a list of such lists sweeps it.
bool is_vector_key(std::string_view path) {
  const std::span<const SceneKey> keys = scene_keys();
  return std::any_of(keys.begin(), keys.end(), [path](const SceneKey& key) {
    return key.path == path && key.value == SceneValue::vector;
  });
}

// One step down from a table: a key, or (after a key holding an array of tables, [[layers]]) the
// index of one of its tables.
struct Step {
  std::string key;
  std::optional<std::size_t> index;
};

// A key of the scene that holds a list of values to sweep over.
struct SweptKey {
  std::vector<Step> path;  // tables down to the key, then the key
  const toml::array* values;
};

// "layers[2].thickness" (indices from 1, as the reader names layers); with `indices` false,
// "layers.thickness" (the schema's path).
std::string join_path(const std::vector<Step>& path, bool indices = true) {
  std::string joined;
  for (const Step& step : path) {
    if (step.index) {
      if (indices) joined += fmt::format("[{}]", *step.index + 1);
      continue;
    }
    if (!joined.empty()) joined += '.';
    joined += step.key;
  }
  return joined;
}

bool plain(const toml::node& node) {
  return !node.is_array() && !node.is_table();
}

bool is_vector(const toml::node& node) {
  const auto* list = node.as_array();
  return list != nullptr && !list->empty() &&
         std::all_of(list->begin(), list->end(), [](const toml::node& v) { return plain(v); });
}

// Every list to sweep over, in file order (toml++ keeps insertion order), down tables and arrays
// of tables.
void find_lists(const toml::table& table, std::vector<Step>& path, std::vector<SweptKey>& found,
                const std::string& origin) {
  for (auto&& [key, node] : table) {
    path.push_back({std::string(key.str()), std::nullopt});
    const auto* list = node.as_array();
    if (const auto* sub = node.as_table()) {
      find_lists(*sub, path, found, origin);
    } else if (list != nullptr && !list->empty() && list->is_array_of_tables()) {
      for (std::size_t i = 0; i < list->size(); ++i) {
        path.push_back({"", i});
        find_lists(*(*list)[i].as_table(), path, found, origin);
        path.pop_back();
      }
    } else if (list != nullptr) {
      const auto& begin = node.source().begin;
      const std::string where = fmt::format(" ({}:{}:{})", origin, begin.line, begin.column);
      const std::string name = join_path(path);
      const bool vector_key = is_vector_key(join_path(path, false));
      if (list->empty()) {
        throw InputError(name, "is an empty list" + where,
                         "a value, or a non-empty list of values to sweep over");
      }
      if (vector_key) {
        // One vector is the key's value; a list of vectors sweeps it.
        if (is_vector(node)) {
          path.pop_back();
          continue;
        }
        if (!std::all_of(list->begin(), list->end(),
                         [](const toml::node& v) { return is_vector(v); })) {
          throw InputError(name, "is a list mixing vectors and other values" + where,
                           "one list [x, y, z], or a list of such lists to sweep over");
        }
      } else if (!std::all_of(list->begin(), list->end(),
                              [](const toml::node& v) { return plain(v); })) {
        throw InputError(name, "is a list holding a list or table" + where,
                         "a value, or a list of plain values to sweep over");
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
  if (const auto* v = node.as_array()) {
    std::string joined;
    for (const toml::node& element : *v)
      joined += (joined.empty() ? "" : ",") + value_label(element);
    return joined;
  }
  return "value";
}

// "albedo" unless another swept key also ends in "albedo"; then the dotted path.
std::string key_label(const std::vector<SweptKey>& swept, std::size_t index) {
  const std::string& last = swept[index].path.back().key;
  for (std::size_t j = 0; j < swept.size(); ++j) {
    if (j != index && swept[j].path.back().key == last) return join_path(swept[index].path);
  }
  return last;
}

// The table of `document` that holds `key` (find_lists found it there, so every step exists).
toml::table& holder(toml::table& document, const SweptKey& key) {
  toml::node* node = &document;
  for (std::size_t depth = 0; depth + 1 < key.path.size(); ++depth) {
    const Step& step = key.path[depth];
    node = step.index ? node->as_array()->get(*step.index) : node->as_table()->get(step.key);
  }
  return *node->as_table();
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

// One point of a file: `text` is the document's own text when it is the file as written (a mesh's
// [mesh] table is then read from it with the file's lines), else the point is written out.
Scene read_scene(const toml::table& root, std::optional<std::string_view> text,
                 const std::string& origin, Validation validation,
                 std::string_view default_geometry) {
  Scene scene = SceneReader(origin, validation).read(root, default_geometry);
  if (root.get("mesh") != nullptr) {
    if (text) {
      scene.mesh_text = std::string(*text);
    } else {
      std::ostringstream written;
      written << toml::toml_formatter(root);
      scene.mesh_text = written.str();
    }
  }
  return scene;
}

}  // namespace

TransportProblem transport_problem(const SceneSpec& spec) {
  return std::visit([](const auto& s) { return transport_problem(s); }, spec);
}

const RunSettings& run_settings(const SceneSpec& spec) {
  return std::visit([](const auto& s) -> const RunSettings& { return s.run; }, spec);
}

std::string fingerprint(const SceneSpec& spec) {
  return std::visit([](const auto& s) { return fingerprint(s); }, spec);
}

TransportOutput run_spec(const SceneSpec& spec, const ProgressCallback& progress,
                         const RunControl& control) {
  return std::visit(
      [&](const auto& s) {
        using Spec = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<Spec, InfiniteMediumSpec>) {
          return run_infinite_medium(s, progress, control);
        } else if constexpr (std::is_same_v<Spec, HalfSpaceSpec>) {
          return run_half_space(s, progress, control);
        } else if constexpr (std::is_same_v<Spec, LitObjectSpec>) {
          return run_lit_sphere(s, progress, control);  // refuses a mesh (lit_object.hpp)
        } else {
          return run_layered_slab(s, progress, control);
        }
      },
      spec);
}

std::string_view Scene::geometry() const {
  switch (spec.index()) {
    case 1:
      return "half_space";
    case 2:
      return mesh_text ? "mesh" : "sphere";
    case 3:
      return "slab";
    default:
      return "infinite";
  }
}

Scene parse_scene(std::string_view toml_text, const std::string& origin, Validation validation,
                  std::string_view default_geometry) {
  return read_scene(parse_toml(toml_text, origin), toml_text, origin, validation, default_geometry);
}

Scene load_scene(const std::filesystem::path& path, Validation validation,
                 std::string_view default_geometry) {
  return parse_scene(read_text(path), path.string(), validation, default_geometry);
}

std::vector<SweepPoint> parse_sweep(std::string_view toml_text, const std::string& origin,
                                    Validation validation, std::string_view default_geometry) {
  const toml::table root = parse_toml(toml_text, origin);
  std::vector<SweptKey> swept;
  std::vector<Step> path;
  find_lists(root, path, swept, origin);
  if (swept.empty())
    return {{"", read_scene(root, toml_text, origin, validation, default_geometry)}};
  check_sweep_size(swept, origin);
  // Each point copies the scene with one value in place of each list, not the lists themselves,
  // so that a sweep costs its points times the size of one scene.
  toml::table scene = root;
  for (const SweptKey& key : swept) holder(scene, key).insert_or_assign(key.path.back().key, 0);
  std::vector<SweepPoint> points;
  // Odometer over the lists, the last fastest.
  std::vector<std::size_t> index(swept.size(), 0);
  while (true) {
    toml::table point = scene;
    std::string label;
    for (std::size_t k = 0; k < swept.size(); ++k) {
      const toml::node& value = *swept[k].values->get(index[k]);
      holder(point, swept[k]).insert_or_assign(swept[k].path.back().key, value);
      label +=
          fmt::format("{}{}={}", label.empty() ? "" : "_", key_label(swept, k), value_label(value));
    }
    points.push_back(
        {label, read_scene(point, std::nullopt, origin, validation, default_geometry)});
    std::size_t k = swept.size();
    while (k > 0 && ++index[k - 1] == swept[k - 1].values->size()) index[--k] = 0;
    if (k == 0) break;
  }
  return points;
}

std::vector<SweepPoint> load_sweep(const std::filesystem::path& path, Validation validation,
                                   std::string_view default_geometry) {
  return parse_sweep(read_text(path), path.string(), validation, default_geometry);
}

}  // namespace scatterlab
