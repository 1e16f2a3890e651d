#include "mesh_view.hpp"

#include <fmt/format.h>

#include <list>
#include <mutex>

#include "request_fields.hpp"
#include "scatterlab/core/error.hpp"

#if SCATTERLAB_EXPLORE_MESH
#include <omp.h>
#include <toml++/toml.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <span>
#include <sstream>
#include <utility>

#include "scatterlab/core/quadrature.hpp"
#include "scatterlab/mesh/mesh_checks.hpp"
#include "scatterlab/models/bssrdf.hpp"
#include "scatterlab/models/diffusion_profile.hpp"
#include "scatterlab/render/point_cloud.hpp"
#include "scatterlab/render/point_octree.hpp"
#include "scatterlab/render/render_scene.hpp"
#endif

namespace scatterlab {

using namespace explore_request;
namespace fs = std::filesystem;

#if SCATTERLAB_EXPLORE_MESH

namespace {

constexpr int kMinPoints = 16, kMaxPoints = 1 << 16;  // a relaxation of 64k points takes seconds
constexpr int kMaxRelaxation = 200;
constexpr std::size_t kCachedMeshes = 6;
// The page's mesh: triangles split in four until their edges are below the cloud's point spacing
// or the mesh would pass this many triangles.
constexpr std::size_t kMaxDisplayTriangles = 1 << 18;
// Without clustering every vertex sums every point: refused past this many evaluations (seconds).
constexpr double kMaxUnclusteredEvaluations = 2e8;
// The exit factor's table for the page: cos theta_o at 64 equal steps in [0, 1].
constexpr int kExitWeightSteps = 64;

const char* const kShapes[] = {"sphere", "bumpy_sphere", "rounded_tile", "box"};

// A mesh with its cloud, and the mesh the page draws (render_scene.hpp's shapes, point_cloud.hpp).
struct PreparedMesh {
  std::string source;  // the shape or the OBJ file, in words
  TriangleMesh mesh;
  PointCloud cloud;
  TriangleMesh display;  // shading normals at every vertex
  double ms = 0.0;       // reading the mesh, the cloud and the display mesh
};

// The mesh the page draws: a flat-faceted mesh's vertices split per triangle (each with its
// facet's normal), then every triangle split in four at its edges' midpoints (shared midpoints,
// normals averaged and normalised) while its longest edge exceeds `spacing` and the count stays
// under kMaxDisplayTriangles: M is drawn by interpolating between vertices, so they must lie no
// farther apart than the cloud's points (a box has only 8 corners).
TriangleMesh display_mesh(const TriangleMesh& mesh, double spacing) {
  TriangleMesh out;
  if (mesh.has_shading_normals()) {
    out = mesh;
  } else {
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
      const auto base = static_cast<std::uint32_t>(out.positions.size());
      for (int c = 0; c < 3; ++c) {
        out.positions.push_back(mesh.vertex(t, c));
        out.normals.push_back(mesh.geometric_normal(t));
      }
      out.triangles.push_back({base, base + 1, base + 2});
    }
  }
  double longest = 0.0;
  for (std::size_t t = 0; t < out.triangle_count(); ++t) {
    for (int c = 0; c < 3; ++c) {
      longest = std::max(longest, (out.vertex(t, c) - out.vertex(t, (c + 1) % 3)).norm());
    }
  }
  while (longest > spacing && 4 * out.triangle_count() <= kMaxDisplayTriangles) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoints;
    const auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      const auto key = std::minmax(a, b);
      const auto [it, added] =
          midpoints.try_emplace(key, static_cast<std::uint32_t>(out.positions.size()));
      if (added) {
        out.positions.push_back(0.5 * (out.positions[a] + out.positions[b]));
        out.normals.push_back((out.normals[a] + out.normals[b]).normalized());
      }
      return it->second;
    };
    std::vector<std::array<std::uint32_t, 3>> split;
    split.reserve(4 * out.triangle_count());
    for (const auto& [a, b, c] : std::vector(out.triangles)) {
      const std::uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      split.push_back({a, ab, ca});
      split.push_back({ab, b, bc});
      split.push_back({ca, bc, c});
      split.push_back({ab, bc, ca});
    }
    out.triangles = std::move(split);
    longest *= 0.5;
  }
  return out;
}

// The request's "mesh" as the [mesh] table of a render scene (render_scene.hpp), read by the
// scene's reader so that its shapes, defaults and refusals ("mesh.radius: ...") are the same.
// An OBJ file's path is an open folder's file (I/NAME), replaced by the file itself.
SceneMesh read_request_mesh(const json& mesh, const std::vector<fs::path>& folders) {
  if (!mesh.is_object()) {
    throw InputError("mesh", "missing or not an object",
                     "{\"shape\": \"sphere\" | \"bumpy_sphere\" | \"rounded_tile\" | \"box\" | "
                     "\"obj\", its parameters (render scene's [mesh]), \"path\": \"I/NAME\" for "
                     "an OBJ file of an open folder}");
  }
  toml::table table;
  for (const auto& [key, value] : mesh.items()) {
    const std::string field = "mesh." + key;
    if (key == "path") {
      if (!value.is_string()) throw InputError(field, "got " + value.dump(), "\"I/NAME\"");
      table.insert(key, resolve_open_file(folders, value.get<std::string>(), field, ".obj",
                                          "an OBJ file (*.obj) that /api/meshes lists")
                            .file.string());
    } else if (value.is_string()) {
      table.insert(key, value.get<std::string>());
    } else if (value.is_number_integer()) {
      table.insert(key, value.get<std::int64_t>());
    } else if (value.is_number()) {
      table.insert(key, value.get<double>());
    } else if (value.is_array()) {
      toml::array array;
      for (const json& element : value) {
        if (!element.is_number()) {
          throw InputError(field, "got " + value.dump(), "an array of numbers");
        }
        array.push_back(element.get<double>());
      }
      table.insert(key, std::move(array));
    } else {
      throw InputError(field, "got " + value.dump(), "a number, a string or an array of numbers");
    }
  }
  std::ostringstream text;
  text << toml::table{{"mesh", std::move(table)}};
  SceneMesh scene_mesh = parse_scene_mesh(text.str(), "the request's mesh");
  // The cloud and the shadow rays assume a closed object, as a render scene does.
  require_closed_mesh(scene_mesh.mesh);
  return scene_mesh;
}

json flat(const std::vector<Vec3>& vectors) {
  std::vector<float> values;
  values.reserve(3 * vectors.size());
  for (const Vec3& v : vectors) {
    for (int k = 0; k < 3; ++k) values.push_back(static_cast<float>(v[k]));
  }
  return values;
}

}  // namespace

struct MeshView::Cache {
  std::mutex mutex;
  std::list<std::pair<std::string, std::shared_ptr<const PreparedMesh>>> entries;  // newest first
};

MeshView::MeshView(std::vector<fs::path> open_folders)
    : open_folders_(std::move(open_folders)), cache_(std::make_unique<Cache>()) {}

MeshView::~MeshView() = default;

std::string MeshView::meshes() const {
  json obj = json::array();
  for (const OpenFile& file : open_files(open_folders_, ".obj")) {
    obj.push_back({{"path", file.path}, {"folder", file.folder.string()}, {"name", file.name}});
  }
  return json{
      {"available", true},
      {"shapes", kShapes},
      {"shape_parameters",
       "those of a render scene's [mesh] table (radius, amplitude, frequency, rings, "
       "segments, half_size, exponent, normals), with its defaults"},
      {"obj_files", obj},
      {"models",
       [] {
         json names = json::array();
         for (const ProfileModel model : all_profile_models) names.push_back(to_string(model));
         return names;
       }()},
      {"defaults", {{"points", 4096}, {"seed", 1}, {"relaxation", 40}, {"cluster_angle", 0.05}}},
      {"limits", {{"points", {kMinPoints, kMaxPoints}}, {"relaxation", {0, kMaxRelaxation}}}}}
      .dump();
}

namespace {

// The kernels of a text model on the cloud's grid (point_octree.hpp), one per channel: its
// values at the table's nodes, and its average over one point's disc, 2 / rho^2 int_0^rho R_d r
// dr, by 64-point Gauss-Legendre (r R_d stays smooth at 0 where R_d ~ 1 / r, as quantized
// diffusion's does); each in one call of the model, which muparser evaluates point by point.
std::vector<RadialKernel> text_model_kernels(const TextModel& model,
                                             const std::map<std::string, double>& parameters,
                                             const std::vector<HalfSpaceMedium>& media,
                                             double point_area, const BoundingBox& bounds) {
  const KernelGrid grid = cloud_kernel_grid(point_area, bounds);
  const std::vector<double> nodes = RadialKernel::node_radii(grid.rho, grid.r_max);
  const GaussLegendre rule = gauss_legendre(64);
  std::vector<double> disc_r(rule.nodes.size());
  for (std::size_t k = 0; k < disc_r.size(); ++k)
    disc_r[k] = 0.5 * grid.rho * (rule.nodes[k] + 1.0);
  std::vector<RadialKernel> kernels;
  for (const HalfSpaceMedium& medium : media) {
    const std::vector<double> values = model.reflectance(medium, parameters, nodes);
    const std::vector<double> near = model.reflectance(medium, parameters, disc_r);
    double integral = 0.0;  // int_0^rho R_d r dr
    for (std::size_t k = 0; k < near.size(); ++k)
      integral += 0.5 * grid.rho * rule.weights[k] * near[k] * disc_r[k];
    kernels.emplace_back(values, 2.0 * integral / (grid.rho * grid.rho), grid.rho, grid.r_max);
  }
  return kernels;
}

}  // namespace

std::string MeshView::exitance(std::string_view body,
                               const std::vector<TextModel>& text_models) const {
  const auto start = std::chrono::steady_clock::now();
  const json request = parse_body(body);

  // The material per channel (api.hpp's medium, one or three), in the mesh's unit.
  const double scale = scale_of(request);
  const auto media_found = request.find("media");
  if (media_found == request.end() || !media_found->is_array() ||
      (media_found->size() != 1 && media_found->size() != 3)) {
    throw InputError("media", "missing, not an array, or not 1 or 3 entries",
                     "[red, green, blue] (or one) media {\"sigma_a\", \"sigma_s_reduced\", "
                     "\"g\", \"eta\"}");
  }
  const json model_value = request.value("model", json("better_dipole"));
  const std::string model_name =
      model_value.is_string() ? model_value.get<std::string>() : model_value.dump();
  // A built-in profile, or a text model (its parameters from request.parameters[name]).
  const std::optional<ProfileModel> built_in = find_profile_model(model_name);
  const auto text_model = std::find_if(text_models.begin(), text_models.end(),
                                       [&](const TextModel& m) { return m.name() == model_name; });
  if (!built_in && text_model == text_models.end()) {
    std::string accepted = "dipole, better_dipole, quantized_diffusion";
    for (const TextModel& m : text_models) accepted += ", " + m.name();
    throw InputError("model", fmt::format("got {}", model_name), accepted);
  }
  const std::map<std::string, double> text_parameters =
      built_in ? std::map<std::string, double>{} : text_model_parameters(request, model_name);
  std::vector<DiffusionProfile> profiles;
  std::vector<HalfSpaceMedium> media;
  double eta = 1.0;
  for (std::size_t c = 0; c < media_found->size(); ++c) {
    const std::string field = fmt::format("media[{}]", c);
    const HalfSpaceMedium medium = medium_of((*media_found)[c], field, scale);
    if (c == 0) eta = medium.eta;
    if (medium.eta != eta) {
      throw InputError(field + ".eta", fmt::format("got {} after {}", medium.eta, eta),
                       "one eta for every channel (the surface's)");
    }
    check_bssrdf_eta(medium.eta, field + ".eta");
    media.push_back(medium);
    if (built_in) profiles.emplace_back(*built_in, medium);
  }

  // The light: towards (azimuth, elevation) in degrees, z up.
  const json light_request = request.value("light", json::object());
  if (!light_request.is_object()) {
    throw InputError("light", "not an object", "{\"azimuth\", \"elevation\" (degrees)}");
  }
  const double azimuth = number(light_request, "azimuth", "light.azimuth", 0.0);
  const double elevation = number(light_request, "elevation", "light.elevation", 45.0);
  if (elevation < -90.0 || elevation > 90.0) {
    throw InputError("light.elevation", fmt::format("got {}", elevation),
                     "degrees in [-90, 90] above the xy plane");
  }
  DirectionalLight light;
  light.irradiance = number(light_request, "irradiance", "light.irradiance", 1.0);
  if (!(light.irradiance >= 0.0)) {
    throw InputError("light.irradiance", fmt::format("got {}", light.irradiance),
                     "a finite number >= 0 (W per length^2 normal to the beam)");
  }
  const double a = azimuth * std::numbers::pi / 180.0, e = elevation * std::numbers::pi / 180.0;
  light.to_light = Vec3(std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e));

  const auto flag = [&](const char* key, bool fallback) {
    const json value = request.value(key, json(fallback));
    if (!value.is_boolean()) throw InputError(key, "got " + value.dump(), "true or false");
    return value.get<bool>();
  };
  const bool occlusion = flag("occlusion", true);
  const bool geometry = flag("geometry", true);
  const double cluster_angle = number(request, "cluster_angle", "cluster_angle", 0.05);
  if (!(cluster_angle >= 0.0)) {
    throw InputError("cluster_angle", fmt::format("got {}", cluster_angle),
                     "a solid angle >= 0 in sr (Bitterli eq. 2.40; 0: every point summed)");
  }
  PointCloudOptions cloud_options;
  cloud_options.points = whole(request, "points", "points", 4096, kMinPoints, kMaxPoints);
  cloud_options.seed = static_cast<std::uint64_t>(
      whole(request, "seed", "seed", 1, 0, std::numeric_limits<int>::max()));
  cloud_options.relaxation = whole(request, "relaxation", "relaxation", 40, 0, kMaxRelaxation);

  // The mesh and its cloud, cached by mesh, points, seed and relaxation.
  const json mesh_request = request.value("mesh", json());
  std::string key = fmt::format("{} points={} seed={} relaxation={}", mesh_request.dump(),
                                cloud_options.points, cloud_options.seed, cloud_options.relaxation);
  std::shared_ptr<const PreparedMesh> prepared;
  bool cached = false;
  // An OBJ file's time of last change is part of the key: an edited file is read again.
  if (mesh_request.is_object() && mesh_request.contains("path") &&
      mesh_request["path"].is_string()) {
    const fs::path file = resolve_open_file(open_folders_, mesh_request["path"].get<std::string>(),
                                            "mesh.path", ".obj", "an OBJ file (*.obj)")
                              .file;
    std::error_code error;
    key += fmt::format(" time={}", fs::last_write_time(file, error).time_since_epoch().count());
  }
  {
    const std::lock_guard lock(cache_->mutex);
    auto& entries = cache_->entries;
    const auto found = std::find_if(entries.begin(), entries.end(),
                                    [&](const auto& entry) { return entry.first == key; });
    if (found != entries.end()) {
      prepared = found->second;
      entries.splice(entries.begin(), entries, found);
      cached = true;
    } else {
      const auto read_start = std::chrono::steady_clock::now();
      SceneMesh scene_mesh = read_request_mesh(mesh_request, open_folders_);
      auto fresh = std::make_shared<PreparedMesh>();
      fresh->source = scene_mesh.source;
      fresh->mesh = std::move(scene_mesh.mesh);
      fresh->cloud = make_point_cloud(fresh->mesh, cloud_options);
      fresh->display = display_mesh(fresh->mesh, fresh->cloud.repulsion_radius);
      fresh->ms = milliseconds_since(read_start);
      prepared = fresh;
      entries.emplace_front(key, std::move(fresh));
      if (entries.size() > kCachedMeshes) entries.pop_back();
    }
  }
  const PointCloud& cloud = prepared->cloud;
  const TriangleMesh& display = prepared->display;
  const std::size_t vertices = display.positions.size();
  if (cluster_angle == 0.0 && static_cast<double>(vertices) * static_cast<double>(cloud.size()) >
                                  kMaxUnclusteredEvaluations) {
    throw InputError("cluster_angle",
                     fmt::format("0 with {} points and {} vertices", cloud.size(), vertices),
                     "a cluster angle > 0, or fewer points");
  }

  // First pass: the power entering at each point (point_cloud.hpp), then the octree.
  auto step = std::chrono::steady_clock::now();
  const std::vector<double> irradiance =
      directional_irradiance(prepared->mesh, cloud, light, eta, occlusion);
  const double ms_irradiance = milliseconds_since(step);
  step = std::chrono::steady_clock::now();
  const PointOctree octree = cloud_octree(cloud, irradiance);
  const std::vector<RadialKernel> kernels =
      built_in ? cloud_kernels(profiles, cloud.point_area, prepared->mesh.bounds())
               : text_model_kernels(*text_model, text_parameters, media, cloud.point_area,
                                    prepared->mesh.bounds());
  const double ms_octree = milliseconds_since(step);

  // Second pass: M at every vertex of the page's mesh (point_octree.hpp).
  step = std::chrono::steady_clock::now();
  const std::size_t channels = media.size();
  std::vector<double> exitance(vertices * channels);
  std::uint64_t evaluations = 0;
  const auto n = static_cast<std::ptrdiff_t>(vertices);
#pragma omp parallel for schedule(dynamic, 64) reduction(+ : evaluations)
  for (std::ptrdiff_t i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    OctreeQuery query;
    octree.exitance(display.positions[k], cluster_angle, kernels,
                    std::span<double>(exitance).subspan(k * channels, channels), query);
    evaluations += query.evaluations;
  }
  const double ms_vertices = milliseconds_since(step);

  // The radiance toward a viewer: L = M w(cos theta_o), w = F_t(eta, cos theta_o) / (pi 4
  // C_phi(1/eta)) (Bitterli eqs. 2.16 and 2.29, models/bssrdf.hpp), tabulated for the page.
  std::vector<double> cosines(kExitWeightSteps + 1), weights(cosines.size());
  for (int k = 0; k <= kExitWeightSteps; ++k) {
    cosines[static_cast<std::size_t>(k)] = static_cast<double>(k) / kExitWeightSteps;
    weights[static_cast<std::size_t>(k)] =
        bssrdf_exit_weight(eta, cosines[static_cast<std::size_t>(k)]);
  }

  json mesh_json{{"key", key},
                 {"source", prepared->source},
                 {"vertices", vertices},
                 {"triangles", display.triangle_count()},
                 {"mesh_triangles", prepared->mesh.triangle_count()},
                 {"bounds",
                  {{prepared->mesh.bounds().lo.x(), prepared->mesh.bounds().lo.y(),
                    prepared->mesh.bounds().lo.z()},
                   {prepared->mesh.bounds().hi.x(), prepared->mesh.bounds().hi.y(),
                    prepared->mesh.bounds().hi.z()}}}};
  if (geometry) {
    std::vector<std::uint32_t> indices;
    indices.reserve(3 * display.triangle_count());
    for (const auto& t : display.triangles) indices.insert(indices.end(), t.begin(), t.end());
    mesh_json["positions"] = flat(display.positions);
    mesh_json["normals"] = flat(display.normals);
    mesh_json["indices"] = indices;
  }
  const auto lit =
      std::count_if(irradiance.begin(), irradiance.end(), [](double value) { return value > 0.0; });
  return json{
      {"mesh", mesh_json},
      {"cloud",
       {{"points", cloud.size()},
        {"point_area", cloud.point_area},
        {"repulsion_radius", cloud.repulsion_radius},
        {"lit_points", lit},
        {"octree_nodes", octree.node_count()},
        {"cached", cached}}},
      {"light",
       {{"to_light", {light.to_light.x(), light.to_light.y(), light.to_light.z()}},
        {"irradiance", light.irradiance},
        {"azimuth", azimuth},
        {"elevation", elevation}}},
      {"model", model_name},
      {"eta", eta},
      {"occlusion", occlusion},
      {"cluster_angle", cluster_angle},
      {"channels", channels},
      {"exitance", exitance},
      {"evaluations_per_vertex",
       vertices > 0 ? static_cast<double>(evaluations) / static_cast<double>(vertices) : 0.0},
      {"exit_weight", {{"cos_outside", cosines}, {"weight", weights}}},
      {"units",
       {{"length", "the plot's unit (the material's length unit times scale)"},
        {"irradiance", "W per length^2 normal to the beam (E_0)"},
        {"exitance",
         "W per length^2: M = sum_p E_t(p) A_p R_d(|x - p|) at each vertex, per "
         "channel (vertex-major)"},
        {"radiance",
         "W per length^2 per sr: L = M * exit_weight(cos theta_o), applied by the "
         "page for its view"}}},
      {"ms",
       {{"mesh_and_cloud", cached ? 0.0 : prepared->ms},
        {"irradiance", ms_irradiance},
        {"octree", ms_octree},
        {"vertices", ms_vertices},
        {"total", milliseconds_since(start)}}}}
      .dump();
}

#else  // without the render component

struct MeshView::Cache {};

MeshView::MeshView(std::vector<fs::path> open_folders)
    : open_folders_(std::move(open_folders)), cache_(std::make_unique<Cache>()) {}

MeshView::~MeshView() = default;

std::string MeshView::meshes() const {
  throw ApiRefusal{501,
                   "the mesh view needs the render component (SCATTERLAB_WITH_RENDER), "
                   "which this program was built without"};
}

std::string MeshView::exitance(std::string_view, const std::vector<TextModel>&) const {
  return meshes();
}

#endif

}  // namespace scatterlab
