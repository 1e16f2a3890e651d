#pragma once
// Fitting every lobe of a simulation file, and writing the fits back into it.
//
// Read:   /grid/{r,z,theta,phi} (attr phi_folded), /tallies/radiance/{mean,stderr}
//         [r, z, theta, phi], and /tallies/flux/mean [r, z, 2] = (E_r, E_z) for the SG axis
//         (computed from the radiance when the file has no flux tally).
// Write:  /fits/<model>/params [r, z, k] (attr names, comma-separated), error [r, z] and
//         error_plane [r, z] (relative L1 errors, lobe_fit.hpp; -1 where not fitted), noise
//         [r, z] (the error an exact model would show), chi2_dof [r, z], status [r, z] int32
//         (attr legend); attrs on /fits/<model> say how it was fitted.
//         The file is copied, the copy gets the fits, and it is renamed over the original, so a
//         failure leaves the original as it was; a re-run replaces /fits/<model>.

#include <cstddef>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "scatterlab/core/work_pace.hpp"
#include "scatterlab/fit/lobe_fit.hpp"
#include "scatterlab/fit/lobe_grid.hpp"
#include "scatterlab/fit/lobe_model.hpp"

namespace scatterlab::fit {

struct RadianceLobes {
  std::filesystem::path path;
  std::vector<double> r_edges, z_edges, theta_edges, phi_edges;
  bool phi_folded = false;
  std::vector<double> mean, stderr_of_mean;  // [r, z, theta, phi]
  std::vector<double> flux;                  // [r, z, 3] = (E_r, E_phi, E_z)
  bool flux_from_tally = false;
  double albedo = std::numeric_limits<double>::quiet_NaN();  // /parameters attrs, NaN if absent
  double g = std::numeric_limits<double>::quiet_NaN();

  std::size_t r_bins() const { return r_edges.size() - 1; }
  std::size_t z_bins() const { return z_edges.size() - 1; }
  std::size_t directions() const { return (theta_edges.size() - 1) * (phi_edges.size() - 1); }
  LobeData lobe(std::size_t r, std::size_t z) const;
};

// Throws InputError("FILE", ...) for a file that is missing, not a scatterlab file, or has no
// radiance tally, or whose radiance does not match its grid.
RadianceLobes read_radiance_lobes(const std::filesystem::path& path);

struct ModelFits {
  LobeModel model;
  std::vector<LobeFit> fits;  // index r * z_bins + z
  double seconds = 0.0;       // thread time spent on its fits, all threads together
};

struct LobeFitRun {
  std::vector<ModelFits> models;  // in the order asked for
  double wall_seconds = 0.0;
  int threads = 1;
  std::size_t attempted_fits = 0;  // Ceres solves (skipped bins not counted)
};

// Fits every spatial bin with every model. Columns of constant r run in parallel (OpenMP,
// `threads` <= 0: all); along z within a column each fit may start from its neighbour's
// solution, so the result is the same for any number of threads. Each fit starts from the
// lowest chi-square of: the data-only estimate, the same bin's solution of the model it
// contains (sg for sg_free, the paper's estimate for dexp, dexp for adexp, adexp for
// adexp_ridge, adexp_ridge for adexp2_ridge; sg_free for asg, through asg_from_sg) and the
// previous z bin's solution; adexp2_ridge is solved from each of its starts and keeps the
// lowest chi-square. Levenberg-Marquardt never raises the cost, so a model ends with a
// chi-square no larger than the model it contains; those models are fitted too when only the
// larger one is asked for.
// progress(spatial bins fitted, bins) is called from one thread as bins finish.
LobeFitRun fit_lobes(const RadianceLobes& lobes, const LobeGrid& grid,
                     const std::vector<LobeModel>& models, const FitOptions& options = {},
                     int threads = 0, const WorkProgress& progress = {});

// Adds /fits/<model> for every model of `run` to lobes.path (see the top of this file).
void write_fits(const RadianceLobes& lobes, const LobeGrid& grid, const LobeFitRun& run,
                const FitOptions& options);

// One file's lobes fitted and written back, as `scatterlab fit FILE` and the Python module's
// scatterlab.fit do: the radiance read (read_radiance_lobes), every spatial bin fitted with every
// model (fit_lobes, on the grid of `quadrature` points per bin and axis, LobeGrid), the summary
// CSV written to `csv` (write_fits_csv) and /fits/<model> added to the file (write_fits).
// InputError("quadrature") for an order outside [1, 8].
struct FileFit {
  RadianceLobes lobes;
  std::size_t theta_bins = 0, phi_bins = 0;  // of the lobe grid
  LobeFitRun run;
};
FileFit fit_file(const std::filesystem::path& path, const std::filesystem::path& csv,
                 const std::vector<LobeModel>& models, const FitOptions& options, int quadrature,
                 int threads, const WorkProgress& progress = {});

// The summary CSV beside a file when none is named: run.h5 -> run-fits.csv.
std::filesystem::path default_fits_csv(const std::filesystem::path& file);

// One row per spatial bin: r_index, z_index, r, z (bin centres, mfp), then per model
// <model>_status, <model>_error, <model>_error_plane, <model>_noise, <model>_chi2_dof and
// <model>_<parameter>. Written to a temporary name and renamed into place.
void write_fits_csv(const std::filesystem::path& path, const RadianceLobes& lobes,
                    const LobeFitRun& run);
// The CSV's header and rows (the field table of field_table.hpp prefixes albedo and g).
std::vector<std::string> fits_csv_header(const LobeFitRun& run);
std::vector<std::vector<std::string>> fits_csv_rows(const RadianceLobes& lobes,
                                                    const LobeFitRun& run);
std::string join_csv(const std::vector<std::string>& fields);

struct ModelFitSummary {
  LobeModel model;
  std::size_t fitted = 0, converged = 0, skipped = 0, failed = 0;
  double median_error = -1, p90_error = -1, median_plane = -1, p90_plane = -1, median_noise = -1;
  // error / noise over the fitted bins, and the fraction of them within 2x the noise.
  double median_ratio = -1, p90_ratio = -1, within_twice_noise = -1;
  double median_chi2_dof = -1, p90_chi2_dof = -1;
  double seconds = 0.0, mean_iterations = 0.0;
};

// Bins where a model ends worse than a model it contains (both fitted): never by chi^2.
struct SupersetCheck {
  LobeModel superset = LobeModel::sg_free, subset = LobeModel::sg;
  std::size_t bins = 0, worse_chi2 = 0, worse_error = 0;
};

struct LobeFitSummary {
  std::vector<ModelFitSummary> models;
  std::vector<SupersetCheck> supersets;
  // Over bins where both (all three) were fitted; -1 when a model was not run.
  double dexp_beats_sg = -1.0;
  double adexp_beats_sg_and_dexp = -1.0;
  double fits_per_second = 0.0;
};

LobeFitSummary summarize(const LobeFitRun& run);
std::string describe(const LobeFitSummary& summary, const LobeFitRun& run);

}  // namespace scatterlab::fit
