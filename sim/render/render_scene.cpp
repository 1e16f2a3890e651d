#include "scatterlab/render/render_scene.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <string_view>
#include <tuple>
#include <vector>

#include "obj_mesh.hpp"
#include "scatterlab/core/constants.hpp"
#include "scatterlab/core/memory_budget.hpp"
#include "scatterlab/core/procedural_meshes.hpp"
#include "scatterlab/io/material_presets.hpp"
#include "scatterlab/io/toml_reader.hpp"
#include "scatterlab/mesh/mesh_checks.hpp"
#include "scatterlab/mesh/mesh_ray_tracer.hpp"

namespace scatterlab {
namespace {

using namespace toml_reading;

// A procedural mesh is built and checked (closed, solid, no part through another:
// mesh/mesh_checks.hpp) before any estimate of a run or an image sees it, and at the peak of those
// checks it holds about 320 bytes per triangle (2.7 GB for the 8.4 million triangles of a sphere
// of 2048 x 2048). A grid of rings x segments makes at most 2 x rings x segments triangles.
constexpr std::uint64_t kMeshBytesPerTriangle = 336;

void check_procedural_mesh_memory(int rings, int segments) {
  const std::uint64_t triangles =
      2 * static_cast<std::uint64_t>(rings) * static_cast<std::uint64_t>(segments);
  MemoryEstimate need;
  need.add(fmt::format("the mesh of {} triangles and its checks", triangles),
           triangles * kMeshBytesPerTriangle);
  check_memory(need, "mesh.rings x mesh.segments", "fewer rings or segments");
}

// The keys each mesh shape takes besides `shape`: a key of another shape is refused, not ignored.
// Every shape takes `normals` (the explorer sends it with each): a box's faces are flat either way.
const std::map<std::string_view, std::vector<std::string_view>>& shape_keys() {
  static const std::map<std::string_view, std::vector<std::string_view>> keys = {
      {"sphere", {"radius", "rings", "segments", "normals"}},
      {"bumpy_sphere", {"radius", "amplitude", "frequency", "rings", "segments", "normals"}},
      {"rounded_tile", {"half_size", "exponent", "rings", "segments", "normals"}},
      {"box", {"half_size", "normals"}},
      {"obj", {"path", "normals"}}};
  return keys;
}

class RenderSceneReader : public TomlReader {
 public:
  RenderSceneReader(const std::string& origin, std::filesystem::path base)
      : TomlReader(origin), base_(std::move(base)) {}

  RenderScene read(const toml::table& root) const {
    check_keys(root, "", {"mesh", "medium", "light", "camera", "image", "floor", "environment"});
    RenderScene scene;
    const toml::table* mesh = subtable(root, "mesh", "");
    if (mesh == nullptr) {
      throw InputError("mesh", "missing",
                       "a [mesh] table with shape = \"sphere\", "
                       "\"bumpy_sphere\", \"rounded_tile\", \"box\" or \"obj\"");
    }
    scene.mesh = read_mesh(*mesh, scene.mesh_file);
    if (const auto* medium = subtable(root, "medium", "")) read_medium(*medium, scene);
    if (const auto* light = subtable(root, "light", "")) read_light(*light, scene.light);
    if (const auto* camera = subtable(root, "camera", "")) read_camera(*camera, scene.camera);
    if (const auto* image = subtable(root, "image", "")) read_image(*image, scene);
    if (const auto* floor = subtable(root, "floor", "")) scene.floor = read_floor(*floor);
    if (const auto* environment = subtable(root, "environment", "")) {
      scene.environment_radiance = read_environment(*environment);
    }
    scene.validate();
    return scene;
  }

  SceneMesh read_mesh_only(const toml::table& root) const {
    const toml::table* table = subtable(root, "mesh", "");
    if (table == nullptr) {
      throw InputError("mesh", "missing", "a [mesh] table with geometry.type = \"mesh\"");
    }
    SceneMesh out;
    std::filesystem::path file;
    out.mesh = read_mesh(*table, file);
    const std::string shape = table->get("shape")->value_or(std::string());
    out.source = file.empty() ? fmt::format("{} of {} triangles", shape, out.mesh.triangle_count())
                              : fmt::format("OBJ file {}", file.string());
    return out;
  }

 private:
  std::optional<Vec3> vec3(const toml::table& table, std::string_view key,
                           const std::string& path) const {
    const toml::node* node = table.get(key);
    if (node == nullptr) return std::nullopt;
    const auto* array = node->as_array();
    const std::string_view accepted = "an array of three finite numbers [x, y, z]";
    if (array == nullptr || array->size() != 3) wrong_type(*node, dotted(path, key), accepted);
    Vec3 v;
    for (std::size_t c = 0; c < 3; ++c) {
      const toml::node& element = *array->get(c);
      if (const auto* x = element.as_floating_point()) {
        v[static_cast<Eigen::Index>(c)] = x->get();
      } else if (const auto* n = element.as_integer()) {
        v[static_cast<Eigen::Index>(c)] = static_cast<double>(n->get());
      } else {
        wrong_type(element, dotted(path, key), accepted);
      }
    }
    if (!v.allFinite()) {
      throw InputError(dotted(path, key), "not finite" + at(*node), std::string(accepted));
    }
    return v;
  }

  double positive(const toml::table& table, std::string_view key, const std::string& path,
                  double fallback) const {
    const auto value = number(table, key, path, "a finite number > 0");
    if (!value) return fallback;
    if (!(*value > 0.0) || !std::isfinite(*value)) {
      throw InputError(dotted(path, key), fmt::format("got {}{}", *value, at(*table.get(key))),
                       "a finite number > 0");
    }
    return *value;
  }

  TriangleMesh read_mesh(const toml::table& table, std::filesystem::path& mesh_file) const {
    const std::string path = "mesh";
    check_keys(table, path,
               {"shape", "path", "normals", "radius", "amplitude", "frequency", "rings", "segments",
                "half_size", "exponent"});
    const std::string_view shapes =
        "\"sphere\", \"bumpy_sphere\", \"rounded_tile\", \"box\" or \"obj\"";
    const auto shape = string(table, "shape", path, shapes);
    if (!shape) throw InputError("mesh.shape", "missing", std::string(shapes));
    const auto taken = shape_keys().find(*shape);
    if (taken == shape_keys().end()) wrong_type(*table.get("shape"), "mesh.shape", shapes);
    for (auto&& [key, node] : table) {
      const std::string_view name = key.str();
      if (name == "shape" ||
          std::find(taken->second.begin(), taken->second.end(), name) != taken->second.end()) {
        continue;
      }
      throw InputError(
          dotted(path, name),
          fmt::format("given for shape \"{}\", which does not take it{}", *shape, at(key.source())),
          fmt::format("for shape \"{}\": {}", *shape, join(taken->second)));
    }
    const std::string_view normal_kinds = "\"interpolated\" or \"flat\"";
    const std::string normals =
        string(table, "normals", path, normal_kinds).value_or("interpolated");
    if (normals != "interpolated" && normals != "flat") {
      wrong_type(*table.get("normals"), "mesh.normals", normal_kinds);
    }
    const bool smooth = normals == "interpolated";
    const double radius = positive(table, "radius", path, 1.0);
    const auto rings = integer_as<int>(table, "rings", path, 3, "an integer in [3, 4096]", 4096);
    const auto segments =
        integer_as<int>(table, "segments", path, 3, "an integer in [3, 4096]", 4096);
    const Vec3 half = vec3(table, "half_size", path).value_or(Vec3(1.0, 1.0, 0.3));
    if (!(half.minCoeff() > 0.0)) {
      throw InputError("mesh.half_size", "not all > 0", "three finite numbers > 0");
    }
    // The shapes' own defaults: the bumpy sphere needs the finer grid for its bumps.
    const bool bumpy = *shape == "bumpy_sphere";
    const int grid_rings = rings.value_or(bumpy ? 71 : 24);
    const int grid_segments = segments.value_or(bumpy ? 72 : 48);
    if (*shape == "sphere" || bumpy || *shape == "rounded_tile") {
      check_procedural_mesh_memory(grid_rings, grid_segments);
    }
    TriangleMesh mesh;
    if (*shape == "sphere") {
      mesh = make_sphere(radius, grid_rings, grid_segments, smooth);
    } else if (*shape == "bumpy_sphere") {
      const double amplitude =
          number(table, "amplitude", path, "a number in [0, 0.5]").value_or(0.08);
      if (!(amplitude >= 0.0 && amplitude <= 0.5)) {
        throw InputError("mesh.amplitude", fmt::format("got {}", amplitude),
                         "a number in [0, 0.5]");
      }
      const int frequency =
          integer_as<int>(table, "frequency", path, 1, "an integer in [1, 64]", 64).value_or(6);
      mesh = make_bumpy_sphere(radius, amplitude, frequency, grid_rings, grid_segments);
      if (!smooth) mesh.normals.clear();
    } else if (*shape == "rounded_tile") {
      const double exponent = positive(table, "exponent", path, 0.3);
      mesh = make_rounded_tile(half.x(), half.y(), half.z(), exponent, grid_rings, grid_segments);
      if (!smooth) mesh.normals.clear();
    } else if (*shape == "box") {
      mesh = make_box(half);
    } else if (*shape == "obj") {
      const auto file = string(table, "path", path, "an OBJ file name");
      if (!file) throw InputError("mesh.path", "missing for shape = \"obj\"", "an OBJ file name");
      std::filesystem::path obj(*file);
      if (obj.is_relative()) obj = base_ / obj;
      mesh = read_obj_mesh(obj, smooth);
      mesh_file = obj;
    }
    mesh.validate();
    return mesh;
  }

  void read_medium(const toml::table& table, RenderScene& scene) const {
    const std::string path = "medium";
    check_keys(table, path, {"sigma_s", "sigma_a", "g", "eta", "material", "length_unit"});
    if (table.get("material") != nullptr) {
      read_material(table, scene);
      return;
    }
    if (table.get("length_unit") != nullptr) {
      throw InputError("medium.length_unit", "given without material",
                       "length_unit with material = \"NAME\" (coefficients are in the unit of "
                       "the scene's lengths)");
    }
    const auto sigma_s = per_channel(table, "sigma_s", path, 1.0);
    const auto sigma_a = per_channel(table, "sigma_a", path, 0.0);
    const auto g = per_channel(table, "g", path, 0.0);
    scene.eta = positive(table, "eta", path, scene.eta);
    if (sigma_s.size() == 1 && sigma_a.size() == 1 && g.size() == 1) {
      scene.medium = Medium::from_coefficients(sigma_a[0], sigma_s[0], g[0], "mesh units");
      return;
    }
    // One of them per channel: all three channels, a single number standing for all.
    const auto channel = [](const std::vector<double>& v, std::size_t c) {
      return v.size() == 1 ? v[0] : v[c];
    };
    scene.channel_media.clear();
    for (std::size_t c = 0; c < 3; ++c) {
      scene.channel_media.push_back(Medium::from_coefficients(
          channel(sigma_a, c), channel(sigma_s, c), channel(g, c), "mesh units"));
    }
    scene.medium = scene.channel_media[1];
  }

  // A number, or [red, green, blue]: one value or three.
  std::vector<double> per_channel(const toml::table& table, std::string_view key,
                                  const std::string& path, double fallback) const {
    const toml::node* node = table.get(key);
    if (node == nullptr) return {fallback};
    const std::string_view accepted = "a finite number, or [red, green, blue]";
    if (node->as_array() == nullptr) {
      const double value = *number(table, key, path, accepted);
      if (!std::isfinite(value)) wrong_type(*node, dotted(path, key), accepted);
      return {value};
    }
    const auto values = vector3(table, key, path, accepted);
    for (const double v : *values) {
      if (!std::isfinite(v)) wrong_type(*node, dotted(path, key), accepted);
    }
    return {values->begin(), values->end()};
  }

  // material = "NAME": the table's three channels (io/material_presets.hpp), in length_unit.
  void read_material(const toml::table& table, RenderScene& scene) const {
    const std::string path = "medium";
    for (const char* key : {"sigma_s", "sigma_a"}) {
      if (table.get(key) != nullptr) {
        throw InputError(dotted(path, key), "given with material",
                         "either material = \"NAME\" or the coefficients, not both");
      }
    }
    MaterialRequest request;
    request.name = *string(table, "material", path, "a material name (data/materials/)");
    request.length_unit = string(table, "length_unit", path, "\"um\", \"mm\", \"cm\" or \"m\"");
    request.g = number(table, "g", path, "a number with |g| < 1");
    const MaterialFields fields{"medium.material", "medium.channel", "medium.length_unit",
                                "medium.g"};
    scene.channel_media.clear();
    double eta = 1.0;
    for (const char* channel : {"red", "green", "blue"}) {
      request.channel = channel;
      const ResolvedMaterial resolved = resolve_material(request, fields);
      scene.channel_media.push_back(resolved.medium);
      eta = resolved.eta;
    }
    scene.medium = scene.channel_media[1];
    scene.eta = positive(table, "eta", path, eta);
  }

  RenderFloor read_floor(const toml::table& table) const {
    const std::string path = "floor";
    check_keys(table, path, {"height", "albedo"});
    RenderFloor floor;
    const auto height = number(table, "height", path, "a finite number (z of the plane)");
    if (!height || !std::isfinite(*height)) {
      throw InputError("floor.height", height ? fmt::format("got {}", *height) : "missing",
                       "a finite number (z of the plane)");
    }
    floor.height = *height;
    const auto albedo = per_channel(table, "albedo", path, 0.5);
    for (std::size_t c = 0; c < 3; ++c) {
      floor.albedo[c] = albedo.size() == 1 ? albedo[0] : albedo[c];
      if (!(floor.albedo[c] >= 0.0 && floor.albedo[c] <= 1.0)) {
        throw InputError("floor.albedo", fmt::format("got {}", floor.albedo[c]),
                         "a number in [0, 1], or [red, green, blue] each in [0, 1]");
      }
    }
    return floor;
  }

  double read_environment(const toml::table& table) const {
    const std::string path = "environment";
    check_keys(table, path, {"radiance"});
    const auto radiance = number(table, "radiance", path, "a finite number >= 0");
    if (!radiance || !(*radiance >= 0.0) || !std::isfinite(*radiance)) {
      throw InputError(
          "environment.radiance", radiance ? fmt::format("got {}", *radiance) : "missing",
          "a finite number >= 0 (radiance from every direction, in the image's units)");
    }
    return *radiance;
  }

  void read_light(const toml::table& table, RenderLight& light) const {
    const std::string path = "light";
    check_keys(table, path, {"position", "intensity", "radius"});
    light.position = vec3(table, "position", path).value_or(light.position);
    light.intensity = positive(table, "intensity", path, light.intensity);
    const auto radius = number(table, "radius", path, "a finite number >= 0");
    if (radius) {
      if (!(*radius >= 0.0) || !std::isfinite(*radius)) {
        throw InputError("light.radius", fmt::format("got {}", *radius), "a finite number >= 0");
      }
      light.radius = *radius;
    }
  }

  void read_camera(const toml::table& table, PinholeCamera& camera) const {
    const std::string path = "camera";
    check_keys(table, path, {"position", "look_at", "up", "fov"});
    camera.position = vec3(table, "position", path).value_or(camera.position);
    camera.look_at = vec3(table, "look_at", path).value_or(camera.look_at);
    camera.up = vec3(table, "up", path).value_or(camera.up);
    camera.fov_degrees = positive(table, "fov", path, camera.fov_degrees);
  }

  void read_image(const toml::table& table, RenderScene& scene) const {
    const std::string path = "image";
    check_keys(table, path, {"width", "height", "samples", "light_samples"});
    // The ranges of render_scene.hpp, as the flags that override these are held to.
    const auto in_range = [&](std::string_view key, int highest, int fallback) {
      return integer_as<int>(table, key, path, 1, fmt::format("an integer in [1, {}]", highest),
                             highest)
          .value_or(fallback);
    };
    scene.width = in_range("width", max_image_side, scene.width);
    scene.height = in_range("height", max_image_side, scene.height);
    scene.samples = in_range("samples", max_samples, scene.samples);
    scene.light_samples = in_range("light_samples", max_light_samples, scene.light_samples);
  }

  std::filesystem::path base_;
};

}  // namespace

Vec3 PinholeCamera::ray_direction(int i, int j, int width, int height) const {
  const Vec3 forward = (look_at - position).normalized();
  const Vec3 right = forward.cross(up).normalized();
  const Vec3 true_up = right.cross(forward);
  const double half_height = std::tan(0.5 * fov_degrees * pi / 180.0);
  const double half_width = half_height * width / height;
  const double u = (2.0 * (i + 0.5) / width - 1.0) * half_width;
  const double v = (1.0 - 2.0 * (j + 0.5) / height) * half_height;
  return (forward + u * right + v * true_up).normalized();
}

void RenderScene::validate() const {
  mesh.validate();
  require_closed_mesh(mesh);
  medium.validate();
  if (!(eta > 0.0) || !std::isfinite(eta)) {
    throw InputError("medium.eta", fmt::format("got {}", eta), "a finite number > 0");
  }
  // A scene built in code reaches here without the reader's checks.
  for (const auto& [name, value, highest] :
       {std::tuple{"image.width", width, max_image_side},
        std::tuple{"image.height", height, max_image_side},
        std::tuple{"image.samples", samples, max_samples},
        std::tuple{"image.light_samples", light_samples, max_light_samples}}) {
    if (value < 1 || value > highest) {
      throw InputError(name, fmt::format("got {}", value),
                       fmt::format("an integer in [1, {}]", highest));
    }
  }
  require_enclosed_volume(mesh);
  require_no_self_intersection(mesh);
  const Vec3 forward = camera.look_at - camera.position;
  if (!(forward.norm() > 0.0) || !(forward.cross(camera.up).norm() > 1e-12 * forward.norm())) {
    throw InputError("camera", "look_at equals position, or up is parallel to the view",
                     "a position, a different look_at and an up not along the view");
  }
  if (!(camera.fov_degrees < 180.0)) {
    throw InputError("camera.fov", fmt::format("got {}", camera.fov_degrees),
                     "a number of degrees in (0, 180)");
  }
  const MeshRayTracer tracer(mesh);
  // Parity of crossings along a ray (an irrational direction, unlikely to graze an edge).
  const Vec3 probe = Vec3(0.5773, 0.6123, 0.5407).normalized();
  if (tracer.count_crossings(light.position, probe) % 2 == 1) {
    throw InputError("light.position", "inside the object", "a point outside the mesh");
  }
  if (light.radius > 0.0) {
    // The sphere light must not touch the mesh either: no vertex within it.
    for (const Vec3& p : mesh.positions) {
      if ((p - light.position).norm() <= light.radius) {
        throw InputError("light.radius", "the light sphere overlaps the object",
                         "a radius that keeps the light sphere outside the mesh");
      }
    }
  }
  if (tracer.count_crossings(camera.position, probe) % 2 == 1) {
    throw InputError("camera.position", "inside the object", "a point outside the mesh");
  }
  for (const Medium& m : channel_media) m.validate();
  if (floor) {
    // Everything above the plane: light reaching the floor comes from above it.
    const double lowest = mesh.bounds().lo.z();
    const auto below = [&](const char* what, double z) {
      throw InputError("floor.height",
                       fmt::format("{} is above the {} (z = {})", floor->height, what, z),
                       "a height below the mesh, the light sphere and the camera");
    };
    if (!std::isfinite(floor->height)) below("mesh", lowest);
    if (floor->height > lowest) below("mesh's lowest point", lowest);
    if (floor->height >= light.position.z() - light.radius) below("light", light.position.z());
    if (floor->height >= camera.position.z()) below("camera", camera.position.z());
  }
}

void refuse_volumetric_only(const RenderScene& scene, const std::string& method) {
  if (scene.floor) {
    throw InputError("floor", "a floor with method " + method,
                     "no [floor] table, or method volumetric");
  }
  if (scene.environment_radiance > 0.0) {
    throw InputError("environment", "an environment with method " + method,
                     "no [environment] table, or method volumetric");
  }
}

RenderScene parse_render_scene(std::string_view toml_text, const std::string& origin,
                               const std::filesystem::path& base) {
  return RenderSceneReader(origin, base).read(parse_toml(toml_text, origin));
}

SceneMesh load_scene_mesh(const std::filesystem::path& scene) {
  return parse_scene_mesh(read_text(scene), scene.string(), scene.parent_path());
}

SceneMesh parse_scene_mesh(std::string_view toml_text, const std::string& origin,
                           const std::filesystem::path& base) {
  return RenderSceneReader(origin, base).read_mesh_only(parse_toml(toml_text, origin));
}

RenderScene load_render_scene(const std::filesystem::path& path) {
  return parse_render_scene(read_text(path), path.string(), path.parent_path());
}

}  // namespace scatterlab
