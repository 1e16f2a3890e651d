#include "scatterlab/explore/api.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>
#include <set>

#include "mesh_view.hpp"
#include "request_fields.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/core/fresnel.hpp"
#include "scatterlab/core/medium.hpp"
#include "scatterlab/io/hdf5_file.hpp"
#include "scatterlab/io/material_presets.hpp"
#include "scatterlab/models/diffusion_profile.hpp"
#include "scatterlab/models/lit_sphere_exitance.hpp"
#include "scatterlab/models/parameter_inversion.hpp"
#include "scatterlab/refract/half_space_single_scatter.hpp"

namespace scatterlab {
namespace {

using namespace explore_request;
using Refusal = ApiRefusal;
namespace fs = std::filesystem;

HalfSpaceMedium request_medium(const json& request) {
  return medium_of(request.value("medium", json()), "medium", scale_of(request));
}

constexpr int kMaxPoints = 2000;       // a plot's width in pixels is less
constexpr int kMaxLitSphereBins = 90;  // 2 degrees apart
constexpr int kMaxLitSphereSamples = 1 << 16;

// The built-in profiles: the diffusion models and the exact single scattering.
struct BuiltIn {
  const char* name;
  const char* label;
  const char* reference;
};
constexpr BuiltIn kBuiltIns[] = {
    {"dipole", "classical dipole", "Jensen et al. 2001; Bitterli 2013 eqs. 2.22, 2.30, 2.37"},
    {"better_dipole", "better dipole", "d'Eon 2012, \"A better dipole\""},
    {"quantized_diffusion", "quantized diffusion",
     "d'Eon & Irving 2011, \"A quantized-diffusion model for rendering translucent materials\""},
    {"single_scatter", "exact single scattering",
     "the once-scattered exitance of the half-space (refract/half_space_single_scatter.hpp)"},
};

// The message may quote what the request sent, which need not be UTF-8 (a path or query
// percent-decoded to any bytes): such bytes are written as U+FFFD, where JSON would throw.
std::string error_json(const std::string& message) {
  return json{{"error", message}}.dump(-1, ' ', false, json::error_handler_t::replace);
}

// The entry transmittance of a beam at normal incidence, 1 - F_r(0) (core/fresnel.hpp).
double entry_transmittance(double eta) {
  return 1.0 - fresnel_dielectric_terms(1.0, eta).reflectance();
}

// r_max when the request leaves it out: ten diffusion lengths 1 / sigma_tr of the classical
// dipole (sigma_tr = sqrt(3 sigma_a sigma_t'), Bitterli eq. 2.22), at most 50 reduced mean free
// paths (without absorption sigma_tr = 0).
double automatic_r_max(const HalfSpaceMedium& medium) {
  const double sigma_tr = std::sqrt(3.0 * medium.sigma_a * medium.reduced_sigma_t());
  return std::min(10.0 / sigma_tr, 50.0 / medium.reduced_sigma_t());
}

json string_list(const std::vector<std::string>& values) {
  return json(values);
}

}  // namespace

bool lies_inside(const fs::path& candidate, const fs::path& folder) {
  std::error_code error;
  const fs::path inside = fs::weakly_canonical(fs::absolute(candidate), error);
  if (error) return false;
  const fs::path root = fs::canonical(folder, error);
  if (error) return false;
  const auto [end, _] = std::mismatch(root.begin(), root.end(), inside.begin(), inside.end());
  return end == root.end();
}

ExploreApi::ExploreApi(ExploreOptions options) : options_(std::move(options)) {
  std::error_code error;
  if (!fs::is_regular_file(options_.page / "index.html", error)) {
    throw InputError("page", fmt::format("{} holds no index.html", options_.page.string()),
                     "the folder of the explorer's page (share/scatterlab/explore when "
                     "installed, web/ in the sources, set up by scripts/setup.sh)");
  }
  options_.page = fs::canonical(options_.page);
  for (fs::path& folder : options_.open_folders) {
    if (!fs::is_directory(folder, error)) {
      throw InputError("open", fmt::format("{} is not a folder", folder.string()),
                       "folders that hold searchlight or lit-sphere files (*.h5)");
    }
    folder = fs::canonical(folder);
  }
  mesh_view_ = std::make_shared<const MeshView>(options_.open_folders);
  if (options_.models) {
    text_models_ =
        std::make_shared<const std::vector<TextModel>>(load_text_models(*options_.models));
  } else {
    text_models_ = std::make_shared<const std::vector<TextModel>>();
  }
}

ExploreApi::~ExploreApi() = default;

std::optional<fs::path> ExploreApi::page_file(std::string_view url_path) const {
  std::string relative(url_path);
  if (relative.empty() || relative == "/") relative = "/index.html";
  // Percent-decoded by the server already; anything odd is simply not a page file.
  if (relative.find('\0') != std::string::npos || relative.front() != '/') return std::nullopt;
  const fs::path candidate = options_.page / fs::path(relative.substr(1));
  std::error_code error;
  if (!lies_inside(candidate, options_.page)) return std::nullopt;
  if (!fs::is_regular_file(candidate, error)) return std::nullopt;
  return fs::canonical(candidate);
}

ApiResponse ExploreApi::handle(std::string_view method, std::string_view path,
                               const std::map<std::string, std::string>& query,
                               std::string_view body) const {
  ApiResponse response;
  const bool get = method == "GET" || method == "HEAD", post = method == "POST";
  try {
    if (path.rfind("/api/", 0) != 0) {
      if (!get) throw Refusal{405, "the page's files are read with GET"};
      const auto file = page_file(path);
      if (!file) {
        throw Refusal{
            lies_inside(options_.page / fs::path(std::string(path)).relative_path(), options_.page)
                ? 404
                : 403,
            fmt::format("{}: no such file of the page", path)};
      }
      static const std::map<std::string, std::string> types{
          {".html", "text/html; charset=utf-8"},
          {".js", "text/javascript; charset=utf-8"},
          {".css", "text/css; charset=utf-8"},
          {".png", "image/png"},
          {".svg", "image/svg+xml"},
          {".json", "application/json"}};
      const auto type = types.find(file->extension().string());
      response.content_type = type != types.end() ? type->second : "application/octet-stream";
      response.file = *file;
      return response;
    }
    const std::string_view gets[] = {"/api/info",  "/api/presets", "/api/models",
                                     "/api/files", "/api/file",    "/api/meshes"};
    const std::string_view posts[] = {"/api/profiles", "/api/invert", "/api/lit_sphere",
                                      "/api/mesh_exitance"};
    const bool is_get = std::find(std::begin(gets), std::end(gets), path) != std::end(gets);
    const bool is_post = std::find(std::begin(posts), std::end(posts), path) != std::end(posts);
    if (!is_get && !is_post) throw Refusal{404, fmt::format("{}: no such API path", path)};
    if (is_get && !get) throw Refusal{405, fmt::format("{} is read with GET", path)};
    if (is_post && !post) throw Refusal{405, fmt::format("{} takes a POST with a JSON body", path)};
    if (path == "/api/info") response.body = info();
    if (path == "/api/presets") response.body = presets();
    if (path == "/api/models") response.body = reload_models();
    if (path == "/api/files") response.body = files();
    if (path == "/api/file") response.body = file(query);
    if (path == "/api/profiles") response.body = profiles(body);
    if (path == "/api/invert") response.body = invert(body);
    if (path == "/api/lit_sphere") response.body = lit_sphere(body);
    if (path == "/api/meshes") response.body = mesh_view_->meshes();
    if (path == "/api/mesh_exitance") {
      std::shared_ptr<const std::vector<TextModel>> text_models;
      {
        const std::lock_guard lock(models_mutex_);
        text_models = text_models_;
      }
      response.body = mesh_view_->exitance(body, *text_models);
    }
  } catch (const Refusal& refusal) {
    response.status = refusal.status;
    response.body = error_json(refusal.message);
  } catch (const InputError& error) {
    response.status = 400;
    response.body = error_json(error.what());
  } catch (const std::exception& error) {
    // A failure of a model or of a file read (HDF5): the request was well formed.
    response.status = 500;
    response.body = error_json(error.what());
  }
  return response;
}

std::string ExploreApi::info() const {
  json built_in = json::array();
  for (const BuiltIn& model : kBuiltIns) {
    built_in.push_back(
        {{"name", model.name}, {"label", model.label}, {"reference", model.reference}});
  }
  json folders = json::array();
  for (const fs::path& folder : options_.open_folders) folders.push_back(folder.string());
  json inversion = json::array();
  for (const HalfSpaceModel model : all_half_space_models) inversion.push_back(to_string(model));
  return json{{"version", SCATTERLAB_VERSION},
              {"models", built_in},
              {"text_models", json::parse(text_models_json())},
              {"inversion_models", inversion},
              {"open_folders", folders},
              {"models_folder", options_.models ? options_.models->string() : ""}}
      .dump();
}

std::string ExploreApi::presets() const {
  json libraries = json::array();
  for (const MaterialLibrary& library : shipped_material_libraries()) {
    json materials = json::array();
    for (const MaterialPreset& preset : library.materials) {
      const std::size_t n = preset.sigma_a.size();
      std::vector<double> reduced(n), g(n, 0.0);
      for (std::size_t c = 0; c < n; ++c) {
        // Jensen's table gives sigma_s' (g free, 0 here); Narasimhan's sigma_s and g, whose
        // sigma_s' = sigma_s (1 - g) (Bitterli 2013 eq. 2.24).
        if (!preset.g.empty()) g[c] = preset.g[c];
        reduced[c] = preset.sigma_s_reduced.empty() ? preset.sigma_s[c] * (1.0 - g[c])
                                                    : preset.sigma_s_reduced[c];
      }
      materials.push_back({{"name", preset.name},
                           {"sigma_a", preset.sigma_a},
                           {"sigma_s_reduced", reduced},
                           {"g", g}});
    }
    libraries.push_back({{"id", library.id},
                         {"citation", library.citation},
                         {"length_unit", library.length_unit},
                         {"eta", library.eta},
                         {"channels", string_list(library.channels)},
                         {"materials", materials}});
  }
  return libraries.dump();
}

std::string ExploreApi::text_models_json() const {
  std::shared_ptr<const std::vector<TextModel>> models;
  {
    const std::lock_guard lock(models_mutex_);
    models = text_models_;
  }
  json list = json::array();
  for (const TextModel& model : *models) {
    json parameters = json::array();
    for (const auto& p : model.parameters()) {
      parameters.push_back(
          {{"name", p.name}, {"min", p.min}, {"max", p.max}, {"default", p.default_value}});
    }
    list.push_back({{"name", model.name()},
                    {"description", model.description()},
                    {"reference", model.reference()},
                    {"file", model.origin()},
                    {"parameters", parameters}});
  }
  return list.dump();
}

std::string ExploreApi::reload_models() const {
  if (options_.models) {
    // A bad file leaves the models as they were and is the answer (400, naming file and line).
    auto models =
        std::make_shared<const std::vector<TextModel>>(load_text_models(*options_.models));
    const std::lock_guard lock(models_mutex_);
    text_models_ = std::move(models);
  }
  return text_models_json();
}

std::string ExploreApi::profiles(std::string_view body) const {
  const json request = parse_body(body);
  const HalfSpaceMedium medium = request_medium(request);
  const int points = whole(request, "points", "points", 256, 2, kMaxPoints);
  const double r_max = number(request, "r_max", "r_max", automatic_r_max(medium));
  if (!(r_max > 0.0)) {
    throw InputError("r_max", fmt::format("got {}", r_max), "a finite number > 0, or leave it out");
  }
  // r_k = r_max k / points, k = 1..points: r = 0 is left out, where quantized diffusion is
  // infinite.
  std::vector<double> r(static_cast<std::size_t>(points));
  for (int k = 0; k < points; ++k) r[static_cast<std::size_t>(k)] = r_max * (k + 1) / points;

  const auto found = request.find("models");
  if (found == request.end() || !found->is_array()) {
    throw InputError("models", "missing or not an array", "an array of model names");
  }
  std::shared_ptr<const std::vector<TextModel>> text_models;
  {
    const std::lock_guard lock(models_mutex_);
    text_models = text_models_;
  }
  json curves = json::array();
  for (const json& entry : *found) {
    const std::string name = entry.is_string() ? entry.get<std::string>() : entry.dump();
    const auto start = std::chrono::steady_clock::now();
    std::vector<double> values(r.size());
    json curve{{"model", name}};
    if (name == "single_scatter") {
      const Medium plain =
          Medium::from_coefficients(medium.sigma_a, medium.sigma_s, medium.g, "mm");
      const double t_in = entry_transmittance(medium.eta);
      for (std::size_t k = 0; k < r.size(); ++k) {
        values[k] = half_space_single_scatter_exitance(plain, medium.eta, r[k]).value / t_in;
      }
    } else if (const std::optional<ProfileModel> built_in = find_profile_model(name)) {
      const DiffusionProfile profile(*built_in, medium);
      for (std::size_t k = 0; k < r.size(); ++k) values[k] = profile.reflectance(r[k]);
      curve["total_reflectance"] = profile.total_reflectance();
    } else {
      const auto model = std::find_if(text_models->begin(), text_models->end(),
                                      [&](const TextModel& m) { return m.name() == name; });
      if (model == text_models->end()) {
        std::string accepted = "dipole, better_dipole, quantized_diffusion, single_scatter";
        for (const TextModel& m : *text_models) accepted += ", " + m.name();
        throw InputError("models", fmt::format("no model {}", name), accepted);
      }
      values = model->reflectance(medium, text_model_parameters(request, name), r);
    }
    curve["ms"] = milliseconds_since(start);
    curve["values"] = values;  // a value that is not finite is written as null
    curves.push_back(std::move(curve));
  }
  return json{{"r", r},
              {"r_max", r_max},
              {"medium",
               {{"sigma_a", medium.sigma_a},
                {"sigma_s", medium.sigma_s},
                {"g", medium.g},
                {"eta", medium.eta},
                {"sigma_s_reduced", medium.reduced_sigma_s()}}},
              {"curves", curves}}
      .dump();
}

std::string ExploreApi::invert(std::string_view body) const {
  const json request = parse_body(body);
  // Not a string: refused as an unknown name is (its JSON shown), not as a JSON type error.
  const json model_value = request.value("model", json("dipole"));
  const std::string name =
      model_value.is_string() ? model_value.get<std::string>() : model_value.dump();
  const HalfSpaceModel model = half_space_model_from_string(name, "model");
  const InvertedCoefficients coefficients =
      invert_reflectance(model, number(request, "R_dr", "R_dr"), number(request, "l_d", "l_d"),
                         number(request, "eta", "eta", 1.0), number(request, "g", "g", 0.0));
  return json{{"reduced_albedo", coefficients.reduced_albedo},
              {"sigma_a", coefficients.sigma_a},
              {"sigma_s", coefficients.sigma_s},
              {"sigma_s_reduced", coefficients.sigma_s * (1.0 - number(request, "g", "g", 0.0))}}
      .dump();
}

std::string ExploreApi::lit_sphere(std::string_view body) const {
  const json request = parse_body(body);
  const HalfSpaceMedium medium = request_medium(request);
  const double radius = number(request, "radius", "radius", 1.0);
  const int bins = whole(request, "bins", "bins", 36, 2, kMaxLitSphereBins);
  const int samples = whole(request, "samples", "samples", 2048, 2, kMaxLitSphereSamples);
  std::vector<double> edges(static_cast<std::size_t>(bins) + 1), centres(edges.size() - 1);
  for (int i = 0; i <= bins; ++i) edges[static_cast<std::size_t>(i)] = std::numbers::pi * i / bins;
  for (std::size_t i = 0; i < centres.size(); ++i) centres[i] = 0.5 * (edges[i] + edges[i + 1]);
  const auto found = request.find("models");
  if (found == request.end() || !found->is_array()) {
    throw InputError("models", "missing or not an array",
                     "an array of dipole, better_dipole, quantized_diffusion");
  }
  json curves = json::array();
  for (const json& entry : *found) {
    const std::string name = entry.is_string() ? entry.get<std::string>() : entry.dump();
    const auto start = std::chrono::steady_clock::now();
    const DiffusionProfile profile(parse_profile_model(name, "models"), medium);
    const LitSphereExitance exitance = lit_sphere_exitance(profile, radius, edges, samples, 1);
    curves.push_back({{"model", name},
                      {"mean", exitance.mean},
                      {"stderr", exitance.stderr_of_mean},
                      {"ms", milliseconds_since(start)}});
  }
  return json{{"psi", centres}, {"psi_edges", edges}, {"curves", curves}}.dump();
}

std::string ExploreApi::files() const {
  json list = json::array();
  for (const OpenFile& file : open_files(options_.open_folders, ".h5")) {
    list.push_back({{"path", file.path}, {"folder", file.folder.string()}, {"name", file.name}});
  }
  return list.dump();
}

namespace {

// A path-traced lit sphere (transport/lit_object.hpp, simulate on a sphere scene) under the
// directional light, for the lit sphere panel (Bitterli §3.1.3: the path tracer beside the
// BSSRDF integrated over the sphere): M(psi) of every order and by order, as the file holds
// them, per unit power meeting the sphere, and the medium, index and radius to compare with.
std::string lit_sphere_file(const std::string& path, const hdf5::Group& root) {
  const hdf5::Group parameters = root.open_group("parameters");
  if (parameters.read_string_attribute("source") != "directional" || !root.has_member("grid/psi") ||
      !root.has_member("grid/azimuth") || root.read_dataset("grid/azimuth").values.size() != 2) {
    throw InputError("path",
                     fmt::format("{} is not a lit sphere under the directional light", path),
                     "a lit sphere's file with source directional and one azimuth bin");
  }
  const std::vector<double> edges = root.read_dataset("grid/psi").values;
  std::vector<double> centres(edges.size() - 1);
  for (std::size_t i = 0; i < centres.size(); ++i) centres[i] = 0.5 * (edges[i] + edges[i + 1]);
  json tallies = json::array();
  const hdf5::Group all = root.open_group("tallies");
  for (const std::string& name : all.member_names()) {
    if (name.rfind("exitance", 0) != 0) continue;
    const hdf5::Group tally = all.open_group(name);
    tallies.push_back({{"name", name},
                       {"description", tally.read_string_attribute("description")},
                       {"mean", tally.read_dataset("mean").values},
                       {"stderr", tally.read_dataset("stderr").values}});
  }
  json medium{{"sigma_a", parameters.read_double_attribute("sigma_a")},
              {"sigma_s", parameters.read_double_attribute("sigma_s")},
              {"g", parameters.read_double_attribute("g")},
              {"eta", parameters.read_double_attribute("eta")},
              {"length_unit", parameters.read_string_attribute("length_unit")}};
  return json{{"path", path},
              {"kind", "lit_sphere"},
              {"psi", centres},
              {"psi_edges", edges},
              {"radius", parameters.read_double_attribute("radius")},
              {"medium", medium},
              {"tallies", tallies}}
      .dump();
}

}  // namespace

std::string ExploreApi::file(const std::map<std::string, std::string>& query) const {
  const auto found = query.find("path");
  if (found == query.end()) {
    throw InputError("path", "missing",
                     "I/NAME: the index I of an open folder and a file's name "
                     "in it (as /api/files lists them)");
  }
  const std::string& path = found->second;
  const fs::path candidate = resolve_open_file(options_.open_folders, path, "path", ".h5",
                                               "a searchlight file (*.h5) that /api/files lists")
                                 .file;
  hdf5::File file = hdf5::File::open_read_only(candidate);
  const hdf5::Group& root = file.root();
  const std::string geometry = root.has_member("parameters")
                                   ? root.open_group("parameters").read_string_attribute("geometry")
                                   : std::string();
  if (geometry == "sphere") return lit_sphere_file(path, root);
  if (geometry != "half_space" || !root.has_member("grid/r")) {
    throw InputError("path",
                     fmt::format("{} is neither a searchlight file nor a lit sphere's", path),
                     "a file written by scatterlab searchlight (geometry half_space) or by "
                     "simulate on a lit-sphere scene under the directional light");
  }
  const hdf5::Group parameters = root.open_group("parameters");
  const std::vector<double> edges = root.read_dataset("grid/r").values;
  std::vector<double> centres(edges.size() > 0 ? edges.size() - 1 : 0);
  for (std::size_t i = 0; i < centres.size(); ++i) centres[i] = 0.5 * (edges[i] + edges[i + 1]);
  // Per unit power entering: the tallies count per unit incident power, of which 1 - F_r(0)
  // entered (the file's specular_reflectance is F_r(0)).
  const double eta = parameters.read_double_attribute("eta");
  const double t_in = entry_transmittance(eta);
  json tallies = json::array();
  const hdf5::Group all = root.open_group("tallies");
  for (const std::string& name : all.member_names()) {
    if (name.rfind("reflectance", 0) != 0) continue;
    const hdf5::Group tally = all.open_group(name);
    if (tally.read_string_attribute("dims") != "r") continue;
    std::vector<double> mean = tally.read_dataset("mean").values;
    std::vector<double> stderr_of_mean = tally.read_dataset("stderr").values;
    for (double& v : mean) v /= t_in;
    for (double& v : stderr_of_mean) v /= t_in;
    tallies.push_back({{"name", name},
                       {"description", tally.read_string_attribute("description")},
                       {"mean", mean},
                       {"stderr", stderr_of_mean}});
  }
  json medium{{"sigma_a", parameters.read_double_attribute("sigma_a")},
              {"sigma_s", parameters.read_double_attribute("sigma_s")},
              {"g", parameters.read_double_attribute("g")},
              {"eta", eta},
              {"length_unit", parameters.read_string_attribute("length_unit")}};
  return json{{"path", path},      {"kind", "searchlight"}, {"r", centres},
              {"r_edges", edges},  {"medium", medium},      {"entry_transmittance", t_in},
              {"tallies", tallies}}
      .dump();
}

}  // namespace scatterlab
