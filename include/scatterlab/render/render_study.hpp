#pragma once
// Error against run time of the four single-scatter methods.
// Each scene is rendered by every method at increasing budgets (straight, walter, holzschuch: a
// budget n is n samples per eye ray, per support interval for holzschuch, and n points on the
// sphere light; pathtrace: Monte Carlo samples per pixel), and each image is compared with a
// reference that none of the ranked runs shares: path tracing at many more samples per pixel,
// with a seed of its own, so that its noise is independent of every ranked image. Path tracing
// sees the sphere light itself and makes no approximation of single scattering, so the methods
// that see the light through points on it (single_scatter_renderer.hpp) are charged with that
// too.
//
// The reference's own noise is measured and subtracted, not assumed away: with per-pixel
// standard errors sigma_R, E[sum (L - R)^2] = sum (L - T)^2 + sum sigma_R^2 for any image L
// independent of it (T the true image), so the error reported is
// sqrt(sum (L - R)^2 - sum sigma_R^2) over sqrt(sum R^2 - sum sigma_R^2) (both unbiased in the
// squares; the first clamped at 0). The reference's relative noise is
// sqrt(sum sigma_R^2 / (sum R^2 - sum sigma_R^2)). The subtraction leaves the squared error
// uncertain by sqrt(2 sum sigma_R^4) at least (the variance of a sum of squared Gaussian
// deviations, L = T), so errors below the resolution (2 sum sigma_R^4)^(1/4) / norm are not
// resolved by the reference: the plot draws that line, and such errors on it.
//
// Writes into the output directory: render_study.csv (scene, method, budget, light_samples,
// seconds, rmse, relative_error, mean_z2, reference_noise, resolution), <scene>_error.png
// (relative error against seconds, both axes logarithmic, one line per method and the
// resolution), and
// <scene>_images.png (reference, then each method at its largest budget, side by side, one
// exposure for all, each titled with its method and budget).

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
  int reference_samples = 1 << 20;  // path-traced samples per pixel of the reference
  int threads = 0;                  // 0: all
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
  double rmse = 0.0;            // radiance units, the reference's noise subtracted (above)
  double relative_error = 0.0;  // the same, relative to the reference's norm (above)
  // pathtrace: mean over pixels with a standard error of ((L - L_ref) / sqrt(se^2 + se_ref^2))^2,
  // about 1 when the two agree; NaN otherwise.
  double mean_z2 = std::numeric_limits<double>::quiet_NaN();
  double reference_noise = 0.0;  // the reference's relative noise (above)
  double resolution = 0.0;       // the smallest relative_error the reference resolves (above)
};

struct ImageErrors {
  double rmse = 0.0;             // sqrt(max(0, sum (L - R)^2 - sum sigma_R^2) / pixels)
  double relative_error = 0.0;   // sqrt(max(0, sum (L - R)^2 - sum sigma_R^2) / norm^2)
  double reference_noise = 0.0;  // sqrt(sum sigma_R^2 / norm^2)
  double resolution = 0.0;       // (2 sum sigma_R^4)^(1/4) / norm
};

// The errors of `image` against a `reference` with per-pixel standard errors `reference_error`
// (all the same size; std::invalid_argument otherwise), norm^2 = sum R^2 - sum sigma_R^2 (see
// above). The relative measures are infinite when norm^2 <= 0.
ImageErrors image_errors(const Image& image, const Image& reference, const Image& reference_error);

// Called before each render of the study with what it is ("tile: run 3 of 17, walter at 4
// samples"); what it returns is given that render's progress (tiles done, of the total).
using StudyProgress = std::function<WorkProgress(const std::string& what)>;

struct RenderStudyResult {
  std::vector<RenderStudyRow> rows;            // every run, references excluded
  std::vector<std::filesystem::path> written;  // every file, in the order written
};

// Runs the study and writes its files into `out_dir` (which must exist: InputError "out"): per
// scene NAME_error.png and NAME_images.png, then render_study.csv. `on_row` is called after
// each run.
RenderStudyResult run_render_study(const std::vector<RenderStudyScene>& scenes,
                                   const RenderStudyOptions& options,
                                   const std::filesystem::path& out_dir,
                                   const std::function<void(const RenderStudyRow&)>& on_row = {},
                                   const StudyProgress& progress = {});

}  // namespace scatterlab
