#pragma once
// The JSON API of `scatterlab explore` and the files it serves, without a socket: each request is
// a method, a path, its query and its body, and each answer a status, a content type and a body
// (or a file to send). server.hpp puts it behind HTTP; the tests call it directly.
//
//   GET  /api/info         the version, the built-in models, the text models, the open folders
//   GET  /api/presets      the material tables (io/material_presets.hpp), per channel
//   GET  /api/models       the text models, read again from the --models folder
//   POST /api/profiles     R_d(r) of the asked models for one material: {"medium": {"sigma_a",
//                          "sigma_s" | "sigma_s_reduced", "g", "eta"}, "scale", "r_max"
//                          (optional), "points", "models": [...], "parameters": {model: {name:
//                          value}}} -> {"r": [...], "curves": [{"model", "values", "ms", ...}]}
//   POST /api/invert       (R_dr, l_d) -> coefficients (models/parameter_inversion.hpp)
//   POST /api/lit_sphere   the exitance of each diffusion model on the lit sphere against the
//                          angle from the lit pole (models/lit_sphere_exitance.hpp)
//   GET  /api/files        the searchlight files (*.h5) in the open folders
//   GET  /api/file?path=I/NAME   the reflectance tallies of file NAME of open folder I
//   GET  /api/meshes       the mesh view's built-in shapes and the OBJ files (*.obj) in the open
//                          folders (explore/mesh_view.hpp)
//   POST /api/mesh_exitance  the BSSRDF on a mesh (Bitterli 2013 §3.1.2): {"mesh": {"shape",
//                          its parameters as a render scene's [mesh] table, or "path": "I/NAME"
//                          of an OBJ file}, "points", "seed", "relaxation", "media": [red, green,
//                          blue] (each a "medium" as above), "scale", "model", "light":
//                          {"azimuth", "elevation" (degrees, z up), "irradiance"}, "occlusion",
//                          "cluster_angle", "geometry"} -> the mesh the page draws (positions,
//                          normals, indices unless geometry is false), the multiple-scattering
//                          exitance M at its vertices per channel, the exit factor's table, the
//                          units and the milliseconds of each step. 501 without the render
//                          component.
//   GET  /, /FILE          the page's files (its folder only)
//
// Units: coefficients in 1 / (the material's length unit); `scale` (> 0) is that unit's length in
// the plot's unit, so the plot's coefficients are the material's times scale (Bitterli 2013
// §3.6.1: the scale of one basic unit in relation to the scatter parameters' unit), and r is in
// the plot's unit. Every profile is per unit power entering the medium: the exact single
// scattering (refract/half_space_single_scatter.hpp, per unit incident power) and the Monte Carlo
// tallies are divided by the entry transmittance 1 - F_r(0).
//
// Bad requests: status 400 with {"error": "<field>: <problem>; accepted: <accepted>"}; a path
// outside the page's folder or the open folders 403; an unknown path 404; a wrong method 405.

#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "scatterlab/explore/text_model.hpp"

namespace scatterlab {

class MeshView;

struct ExploreOptions {
  std::filesystem::path page;                       // the page's folder (index.html, ...)
  std::vector<std::filesystem::path> open_folders;  // --open: files the page may read
  std::optional<std::filesystem::path> models;      // --models: text models (*.toml)
};

struct ApiResponse {
  int status = 200;
  std::string content_type = "application/json";
  std::string body;
  std::filesystem::path file;  // when set, the body is this file's contents (static files)
};

class ExploreApi {
 public:
  // Checks the folders (InputError "page", "open", "models") and loads the text models (a bad
  // file is TextModel's InputError).
  explicit ExploreApi(ExploreOptions options);
  ~ExploreApi();

  ApiResponse handle(std::string_view method, std::string_view path,
                     const std::map<std::string, std::string>& query, std::string_view body) const;

  // The page's file at `url_path` ("/" is index.html), or nullopt when it is outside the page's
  // folder (after symbolic links), missing, or not a regular file.
  std::optional<std::filesystem::path> page_file(std::string_view url_path) const;

  const ExploreOptions& options() const { return options_; }

 private:
  std::string info() const;
  std::string presets() const;
  std::string text_models_json() const;
  std::string reload_models() const;
  std::string profiles(std::string_view body) const;
  std::string invert(std::string_view body) const;
  std::string lit_sphere(std::string_view body) const;
  std::string files() const;
  std::string file(const std::map<std::string, std::string>& query) const;

  ExploreOptions options_;
  mutable std::mutex models_mutex_;  // the server answers on several threads
  mutable std::shared_ptr<const std::vector<TextModel>> text_models_;
  std::shared_ptr<const MeshView> mesh_view_;  // its own cache of meshes and point clouds
};

// The inclusive-of-nothing check every served path goes through: `candidate` (made absolute and
// canonical, symbolic links followed) lies inside the canonical `folder`.
bool lies_inside(const std::filesystem::path& candidate, const std::filesystem::path& folder);

}  // namespace scatterlab
