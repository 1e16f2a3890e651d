#include "scatterlab/io/scene_schema.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <deque>
#include <map>
#include <string>

#include "scatterlab/core/constants.hpp"
#include "scatterlab/io/scene.hpp"
#include "scatterlab/transport/declared_tally.hpp"

namespace scatterlab {
namespace {

using enum SceneValue;

// Geometry sets, as SceneKey::geometries spells them.
constexpr std::string_view kAll = "infinite half_space sphere mesh slab";
constexpr std::string_view kMedium = "infinite half_space sphere mesh";
constexpr std::string_view kObject = "sphere mesh";

// Every key of every geometry (io/scene.hpp). The readers' numbers are checked for their ranges
// by each spec's validate(); `accepted` says the same in words.
constexpr std::array kKeys = std::to_array<SceneKey>({
    {"geometry.type", kAll, string, "\"infinite\" \"half_space\" \"sphere\" \"mesh\" \"slab\"",
     "the geometry; \"infinite\" when the file names none (searchlight: \"half_space\")", true},
    {"geometry.eta", "half_space sphere mesh", number, "a number in [0.1, 10]",
     "relative index n_medium / n_outside; 1 for no interface"},
    {"geometry.radius", "sphere", number, "a finite number > 0",
     "the sphere's radius, in "
     "medium.length_unit"},
    {"geometry.length_unit", "slab", string, "\"mfp\" \"um\" \"mm\" \"cm\" \"m\"",
     "the unit of the layers' lengths (cm by default)", true},
    {"geometry.n_above", "slab", number, "a refractive index in [0.1, 10]",
     "the index above the slab"},
    {"geometry.n_below", "slab", number, "a refractive index in [0.1, 10]",
     "the index below the slab"},
    {"surface.eta", "half_space", number, "a finite number > 0",
     "the same as geometry.eta, as older files say"},

    {"medium.albedo", kMedium, number, "a number in [0, 1]", "single-scattering albedo"},
    {"medium.sigma_t", kMedium, number, "a finite number > 0",
     "extinction coefficient, in 1/length_unit"},
    {"medium.g", kMedium, number, "a number with |g| < 1", "Henyey-Greenstein mean cosine"},
    {"medium.sigma_a", kMedium, number, "a finite number >= 0",
     "absorption coefficient, in 1/length_unit (with sigma_s, in place of albedo and sigma_t)"},
    {"medium.sigma_s", kMedium, number, "a finite number >= 0",
     "scattering coefficient, in 1/length_unit"},
    {"medium.length_unit", kMedium, string, "\"mfp\" \"um\" \"mm\" \"cm\" \"m\"",
     "the unit of every length of the scene (mfp by default; mm with sigma_a and sigma_s)", true},
    {"medium.material", kMedium, string, "a material name from data/materials, e.g. \"apple\"",
     "a measured material, in place of the coefficients (scatterlab materials lists them)"},
    {"medium.channel", kMedium, string, "a channel of the material's table, e.g. \"red\"",
     "the material's colour channel"},

    {"layers.mu_a", "slab", number, "a finite number >= 0",
     "the layer's absorption coefficient, in 1/geometry.length_unit"},
    {"layers.mu_s", "slab", number, "a finite number >= 0",
     "the layer's scattering coefficient, in 1/geometry.length_unit"},
    {"layers.g", "slab", number, "a number with |g| < 1", "the layer's mean cosine"},
    {"layers.n", "slab", number, "a refractive index in [0.1, 10]", "the layer's index"},
    {"layers.thickness", "slab", number, "a number > 0, or inf (the last layer)",
     "the layer's thickness, in geometry.length_unit"},
    {"layers.material", "slab", string, "a material name from data/materials, e.g. \"skin1\"",
     "a measured material, in place of mu_a, mu_s (and g, n unless given)"},
    {"layers.channel", "slab", string, "a channel of the material's table, e.g. \"red\"",
     "the material's colour channel"},

    {"mesh.shape", "mesh", string, "\"sphere\" \"bumpy_sphere\" \"rounded_tile\" \"box\" \"obj\"",
     "the object's shape", true},
    {"mesh.path", "mesh", string, "an OBJ file, relative to the scene's folder",
     "the OBJ file of shape \"obj\""},
    {"mesh.normals", "mesh", string, "\"interpolated\" \"flat\"", "the shading normals", true},
    {"mesh.radius", "mesh", number, "a finite number > 0", "a sphere's radius"},
    {"mesh.amplitude", "mesh", number, "a number in [0, 0.5]", "a bumpy sphere's bumps"},
    {"mesh.frequency", "mesh", integer, "an integer in [1, 64]", "a bumpy sphere's bumps"},
    {"mesh.rings", "mesh", integer, "an integer in [3, 4096]", "a sphere's tessellation"},
    {"mesh.segments", "mesh", integer, "an integer in [3, 4096]", "a sphere's tessellation"},
    {"mesh.half_size", "mesh", vector, "three finite numbers > 0", "a box's or tile's half size"},
    {"mesh.exponent", "mesh", number, "a number > 0", "a rounded tile's corners"},

    {"source.type", "infinite", string, "\"beam\" \"point\"",
     "a pencil beam along +z, or an isotropic point source", true},
    {"source.type", kObject, string, "\"directional\" \"pole_beam\" \"beam\" \"sphere\"",
     "the light: along +z, a beam at the pole, a beam from origin along direction, or a sphere "
     "of light (on a mesh)",
     true},
    {"source.incidence_deg", "half_space", number, "an angle in [0, 90) degrees",
     "the beam's angle from the surface normal"},
    {"source.origin", kObject, vector, "three numbers [x, y, z]",
     "a beam's origin, outside the object, in medium.length_unit"},
    {"source.direction", kObject, vector, "three numbers [x, y, z]", "a beam's direction"},
    {"source.position", kObject, vector, "three numbers [x, y, z]",
     "the centre of a sphere of light, in medium.length_unit"},
    {"source.radius", kObject, number, "a finite number > 0",
     "the radius of a sphere of light, in medium.length_unit"},

    {"grid.r.max", "infinite half_space slab", number, "a finite number > 0",
     "the radial grid's extent, in the length unit"},
    {"grid.r.bins", "infinite half_space slab", integer, "an integer in [1, 100000]",
     "radial bins"},
    {"grid.z.min", "infinite", number, "a finite number", "the axial grid's start"},
    {"grid.z.max", "infinite half_space slab", number, "a finite number",
     "the axial (depth) grid's end, in the length unit"},
    {"grid.z.bins", "infinite half_space slab", integer, "an integer in [1, 100000]",
     "axial (depth) bins"},
    {"grid.theta.bins", "infinite", integer, "an integer in [1, 100000]",
     "polar-angle bins over [0, pi]"},
    {"grid.phi.bins", "infinite", integer, "an even integer in [2, 100000]",
     "azimuth bins over [0, 2 pi] (over [0, pi] with fold_phi)"},
    {"grid.fold_phi", "infinite", boolean, "true or false",
     "fold the azimuth onto [0, pi] (L is even in phi)"},
    {"grid.rho.max", "infinite", number, "a finite number > 0",
     "the spherical shells' extent, in the length unit"},
    {"grid.rho.bins", "infinite", integer, "an integer in [1, 100000]", "spherical shells"},
    {"grid.theta_o.bins", "half_space slab", integer, "an integer in [1, 100000]",
     "exit-angle bins over [0, pi/2]"},
    {"grid.x.min", "half_space", number, "a finite number", "the exitance map's x cells"},
    {"grid.x.max", "half_space", number, "a finite number", "the exitance map's x cells"},
    {"grid.x.bins", "half_space", integer, "an integer in [1, 100000]",
     "the exitance map's x cells"},
    {"grid.y.min", "half_space", number, "a finite number", "the exitance map's y cells"},
    {"grid.y.max", "half_space", number, "a finite number", "the exitance map's y cells"},
    {"grid.y.bins", "half_space", integer, "an integer in [1, 100000]",
     "the exitance map's y cells"},
    {"grid.psi.bins", "sphere", integer, "an integer in [1, 100000]",
     "bins of the angle from the lit pole, over [0, pi]"},
    {"grid.azimuth.bins", "sphere", integer, "an integer in [1, 100000]",
     "azimuth bins about z from +x, over [0, 2 pi]"},

    {"tally.name", kAll, string, "1 to 64 letters, digits and _",
     "a declared tally's name (transport/declared_tally.hpp), unique in the file"},
    {"tally.score", kAll, string,
     "\"exitance\" \"transmittance\" \"fluence\" \"absorbed\" \"collisions\" \"path_length\"",
     "what it adds up: light leaving through the lit surface, through a slab's far side, the "
     "fluence rate at collisions, the power absorbed, the collisions, or the path of the light "
     "leaving through the lit surface times its power",
     true},
    {"tally.group_index", "infinite", number, "a refractive index in [0.1, 10]",
     "the medium's group index, for the time of flight (the infinite medium has no index)"},
    {"tallies.radiance", "infinite", boolean, "true or false", "L(r, z, theta, phi)"},
    {"tallies.fluence", "infinite half_space", boolean, "true or false", "fluence phi(r, z)"},
    {"tallies.flux", "infinite", boolean, "true or false", "vector irradiance E(r, z)"},
    {"tallies.fluence_spherical", "infinite", boolean, "true or false",
     "fluence on spherical shells (the point source's)"},
    {"tallies.exitance_map", "half_space", boolean, "true or false",
     "exitance on the x-y cells of the surface"},
    {"tallies.split_by_order", "infinite sphere mesh slab", boolean, "true or false",
     "also unscattered, once- and multiply-scattered light apart"},
    {"tallies.estimator", "infinite", string, "\"collision\" \"track_length\"",
     "estimator of the volume tallies", true},

    {"run.photons", kAll, integer, "an integer >= 1 (1e8 is accepted)", "photons to trace"},
    {"run.batches", kAll, integer, "an integer in [2, run.photons]",
     "batches, for the standard errors"},
    {"run.seed", kAll, integer, "an integer in [0, 2^63 - 1]", "the random streams' seed"},
    {"run.threads", kAll, integer, "an integer >= 0 (0: every core)", "threads"},
    {"run.escape_radius", "infinite half_space slab", number, "a number > 0, or inf",
     "photons past this distance escape, in the length unit"},
    {"run.weighting", "slab", string, "\"analog\" \"implicit\"",
     "analog absorption, or implicit capture with roulette", true},

    {"output.path", kAll, string, "a non-empty file name", "the HDF5 file the run writes"},
});

// An angle's range as the key reference writes it.
std::string range_text(double range) {
  if (range == 0.5 * pi) return "pi/2";
  if (range == pi) return "pi";
  return range == 2.0 * pi ? "2 pi" : fmt::format("{}", range);
}

// kKeys, with the keys of the declared tallies' filters after tally.group_index, written from
// the filters' own rows (transport/declared_tally.hpp), which no one copies here.
const std::vector<SceneKey>& all_keys() {
  static const struct Table {
    std::deque<std::string> text;  // the written paths and meanings, which the keys view
    std::vector<SceneKey> keys;

    std::string_view hold(std::string s) { return text.emplace_back(std::move(s)); }
    void add_filters() {
      constexpr std::string_view bins = "an integer in [1, 100000]";
      for (const DeclaredFilterKey& f : declared_filter_schema()) {
        const std::string at = fmt::format("tally.filters.{}", f.key);
        if (f.axis == FilterAxis::each) {
          keys.push_back({hold(at), f.geometries, boolean, "true or false", f.meaning});
          continue;
        }
        if (f.axis == FilterAxis::angle) {
          keys.push_back({hold(at + ".bins"), f.geometries, integer, bins,
                          hold(fmt::format("{}, over [0, {}]", f.meaning, range_text(f.range)))});
          continue;
        }
        if (f.axis == FilterAxis::count) {
          keys.push_back({hold(at + ".bins"), f.geometries, integer, bins, f.meaning});
          continue;
        }
        const std::string_view meaning = hold(fmt::format(
            "{}, in {}", f.meaning, f.axis == FilterAxis::seconds ? "seconds" : "the length unit"));
        keys.push_back({hold(at + ".min"), f.geometries, number,
                        f.axis == FilterAxis::signed_length ? "a finite number"
                                                            : "a finite number >= 0 (0 by default)",
                        meaning});
        keys.push_back({hold(at + ".max"), f.geometries, number, "a finite number > min", meaning});
        keys.push_back({hold(at + ".bins"), f.geometries, integer, bins, f.meaning});
      }
    }
    Table() {
      for (const SceneKey& key : kKeys) {
        keys.push_back(key);
        if (key.path == "tally.group_index") add_filters();
      }
    }
  } table;
  return table.keys;
}

bool in_list(std::string_view list, std::string_view word) {
  std::size_t at = 0;
  while (at <= list.size()) {
    const std::size_t end = std::min(list.find(' ', at), list.size());
    if (list.substr(at, end - at) == word) return true;
    at = end + 1;
  }
  return false;
}

std::vector<std::string_view> split(std::string_view path) {
  std::vector<std::string_view> parts;
  std::size_t at = 0;
  while (true) {
    const std::size_t dot = path.find('.', at);
    parts.push_back(path.substr(at, dot == std::string_view::npos ? dot : dot - at));
    if (dot == std::string_view::npos) return parts;
    at = dot + 1;
  }
}

std::string json_string(std::string_view text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

// A key's value as JSON Schema: its type (a string of fixed choices as an enum), or a list of
// such values to sweep over.
std::string value_schema(const SceneKey& key) {
  std::string one;
  switch (key.value) {
    case number:
      // TOML's inf reads as a number; JSON has no literal for it, and editors let it through.
      one = R"({"type": "number"})";
      break;
    case integer:
      // 1e7-style floats that are whole numbers are accepted too.
      one = R"({"type": "number", "multipleOf": 1})";
      break;
    case boolean:
      one = R"({"type": "boolean"})";
      break;
    case vector:
      one = R"({"type": "array", "items": {"type": "number"}, "minItems": 3, "maxItems": 3})";
      break;
    case string:
      if (key.choices) {
        std::string names;
        for (std::size_t at = 0; at < key.accepted.size();) {
          const std::size_t end = std::min(key.accepted.find(' ', at), key.accepted.size());
          names += (names.empty() ? "" : ", ") + std::string(key.accepted.substr(at, end - at));
          at = end + 1;
        }
        one = fmt::format(R"({{"enum": [{}]}})", names);
      } else {
        one = R"({"type": "string"})";
      }
      break;
  }
  return fmt::format(
      R"({{"description": {}, "anyOf": [{}, {{"type": "array", "items": {}, "minItems": 1}}]}})",
      json_string(fmt::format("{} ({})", key.meaning, key.accepted)), one, one);
}

// The tables and keys of one geometry, nested by their paths.
struct Node {
  std::map<std::string, Node> children;
  std::vector<std::string> order;
  const SceneKey* key = nullptr;
};

std::string node_schema(const Node& node, bool array_of_tables) {
  if (node.key != nullptr) return value_schema(*node.key);
  std::string properties;
  for (const std::string& name : node.order) {
    const bool layers = name == "layers" || name == "tally";  // arrays of tables
    properties += fmt::format("{}{}: {}", properties.empty() ? "" : ", ", json_string(name),
                              node_schema(node.children.at(name), layers));
  }
  const std::string table = fmt::format(
      R"({{"type": "object", "properties": {{{}}}, "additionalProperties": false}})", properties);
  if (!array_of_tables) return table;
  return fmt::format(R"({{"type": "array", "items": {}, "minItems": 1}})", table);
}

std::string geometry_schema(std::string_view geometry) {
  Node root;
  for (const SceneKey& key : all_keys()) {
    if (!in_list(key.geometries, geometry)) continue;
    Node* node = &root;
    for (const std::string_view part : split(key.path)) {
      const std::string name(part);
      if (!node->children.contains(name)) node->order.push_back(name);
      node = &node->children[name];
    }
    node->key = &key;
  }
  return node_schema(root, false);
}

}  // namespace

std::span<const SceneKey> scene_keys() {
  return all_keys();
}

bool scene_key_of(const SceneKey& key, std::string_view geometry) {
  return in_list(key.geometries, geometry);
}

std::vector<std::string_view> scene_table_keys(std::string_view geometry, std::string_view table) {
  const std::vector<std::string_view> prefix =
      table.empty() ? std::vector<std::string_view>{} : split(table);
  std::vector<std::string_view> names;
  for (const SceneKey& key : all_keys()) {
    if (!in_list(key.geometries, geometry)) continue;
    const std::vector<std::string_view> parts = split(key.path);
    if (parts.size() <= prefix.size() || !std::equal(prefix.begin(), prefix.end(), parts.begin())) {
      continue;
    }
    const std::string_view name = parts[prefix.size()];
    if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
  }
  return names;
}

// The condition "geometry.type is `geometry`" of one if/then branch.
std::string geometry_type_is(std::string_view geometry) {
  return fmt::format(R"({{"required": ["geometry"], "properties": {{"geometry": )"
                     R"({{"required": ["type"], "properties": {{"type": {{"const": {}}}}}}}}}}})",
                     json_string(geometry));
}

std::string scene_json_schema() {
  // One branch per geometry: the file's geometry.type picks it (none: the infinite medium, and
  // an infinite-medium file that names its geometry takes the same branch).
  constexpr std::string_view kNoType =
      R"({"not": {"required": ["geometry"], "properties": {"geometry": {"required": ["type"]}}}})";
  std::string branches, types;
  for (const std::string_view geometry : scene_geometries) {
    const std::string condition =
        geometry == "infinite"
            ? fmt::format(R"({{"anyOf": [{}, {}]}})", kNoType, geometry_type_is(geometry))
            : geometry_type_is(geometry);
    branches += fmt::format("{}\n    {{\"if\": {}, \"then\": {}}}", branches.empty() ? "" : ",",
                            condition, geometry_schema(geometry));
    types += fmt::format("{}{}", types.empty() ? "" : ", ", json_string(geometry));
  }
  return fmt::format(
      "{{\n  \"$schema\": \"https://json-schema.org/draft/2020-12/schema\",\n"
      "  \"title\": \"scatterlab scene\",\n"
      "  \"description\": \"A scene file of scatterlab simulate (io/scene.hpp); any value may be "
      "a list of values, a sweep\",\n"
      "  \"type\": \"object\",\n"
      "  \"properties\": {{\"geometry\": {{\"type\": \"object\", \"properties\": {{\"type\": "
      "{{\"enum\": [{}]}}}}}}}},\n"
      "  \"allOf\": [{}\n  ]\n}}\n",
      types, branches);
}

std::string scene_key_reference() {
  std::string text =
      "# Scene keys\n\n"
      "Written by `scatterlab scene --keys` from the program's one table of keys "
      "(`include/scatterlab/io/scene_schema.hpp`); `scatterlab scene --schema` writes the same "
      "as a JSON Schema. Any value may be a list of values: the file is then a sweep, one run "
      "per combination (`[[layers]]` keys included; a vector key is swept by a list of "
      "vectors).\n";
  for (const std::string_view geometry : scene_geometries) {
    text += fmt::format(
        "\n## geometry.type = \"{}\"\n\n| key | value | accepted | meaning |\n"
        "|---|---|---|---|\n",
        geometry);
    for (const SceneKey& key : all_keys()) {
      if (!in_list(key.geometries, geometry)) continue;
      constexpr std::array<std::string_view, 5> kinds = {"number", "integer", "boolean", "string",
                                                         "[x, y, z]"};
      // A bar inside a Markdown table's cell is escaped.
      std::string accepted;
      for (const char c : key.accepted)
        accepted += c == '|' ? std::string("\\|") : std::string(1, c);
      text += fmt::format("| `{}` | {} | {} | {} |\n", key.path,
                          kinds[static_cast<std::size_t>(key.value)], accepted, key.meaning);
    }
  }
  return text;
}

}  // namespace scatterlab
