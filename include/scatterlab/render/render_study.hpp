#pragma once
// Error against run time of the four single-scatter methods (issue: "error against run time").
// Each scene is rendered by every method at increasing budgets (straight, walter, holzschuch: a
// budget n is n samples per eye ray, per support interval for holzschuch, and n points on the
// sphere light; pathtrace: Monte Carlo samples per pixel), and each image is compared with a
// converged reference: holzschuch at a high sample count and as many light points as the
// largest budget. Holzschuch's points lie inside one triangle's support interval (Holzschuch 2013,
// §3.2), where the integrand is smooth, so its midpoint sums converge fastest; walter's points
// straddle the interval ends, where the number of refracted paths jumps. The deterministic runs
// see the sphere light through points on it (single_scatter_renderer.hpp), as many as the
// budget; pathtrace sees the sphere itself and is the independent check of the reference: its
// mean z^2 against it (lit pixels) tends to 1 when the two agree, and grows with the samples
// when they do not.
//
// Writes into the output directory: render_study.csv (scene, method, budget, light_samples,
// seconds, rmse, relative_error, mean_z2), <scene>_error.png (relative error against seconds,
// both axes logarithmic, one line per method), and <scene>_images.png (reference, then each
// method at its largest budget, side by side, one exposure for all, each titled with its method
// and budget).

#include <filesystem>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "scatterlab/render/image_file.hpp"
#include "scatterlab/render/render_scene.hpp"
#include "scatterlab/render/single_scatter_renderer.hpp"

namespace scatterlab {

struct RenderStudyScene {
  std::string name;  // file stem, used in the CSV and the file names
  RenderScene scene;
};

struct RenderStudyOptions {
  int size = 32;                                // width = height of every image
  std::vector<int> budgets = {1, 2, 4, 8, 16};  // samples per ray and light points (see above)
  std::vector<int> pathtrace_budgets = {4000, 16000, 64000, 256000};  // samples per pixel
  int reference_samples = 64;        // holzschuch samples per interval of the reference
  int reference_light_samples = 16;  // points on the sphere light for the reference
  int threads = 0;                   // 0: all
  std::uint64_t seed = 1;

  // Small images and budgets: seconds on two cores (a smoke test of the whole study).
  static RenderStudyOptions quick();
};

struct RenderStudyRow {
  std::string scene;
  RenderMethod method = RenderMethod::straight;
  int budget = 0;         // samples per ray (per interval for holzschuch; per pixel for pathtrace)
  int light_samples = 0;  // points on the light (0 for pathtrace)
  double seconds = 0.0;
  double rmse = 0.0;            // sqrt(mean over pixels of (L - L_ref)^2), radiance units
  double relative_error = 0.0;  // ||L - L_ref||_2 / ||L_ref||_2 over the image
  // pathtrace: mean over pixels with a standard error of ((L - L_ref) / stderr)^2; NaN otherwise.
  double mean_z2 = std::numeric_limits<double>::quiet_NaN();
};

// RMSE and relative error of `image` against `reference` (same size; std::invalid_argument
// otherwise). The relative error is infinite for an all-zero reference.
void image_errors(const Image& image, const Image& reference, double& rmse, double& relative_error);

// Runs the study and writes its files into `out_dir` (which must exist: InputError "out").
// `on_row` is called after each run (for progress). Returns every row, references excluded.
std::vector<RenderStudyRow> run_render_study(
    const std::vector<RenderStudyScene>& scenes, const RenderStudyOptions& options,
    const std::filesystem::path& out_dir,
    const std::function<void(const RenderStudyRow&)>& on_row = {});

}  // namespace scatterlab
