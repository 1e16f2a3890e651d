#include "scatterlab/fit/lobe_fits_file.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "scatterlab/core/error.hpp"
#include "scatterlab/core/memory_budget.hpp"
#include "scatterlab/io/atomic_output.hpp"
#include "scatterlab/io/hdf5_file.hpp"
#include "scatterlab/io/simulation_file.hpp"

namespace scatterlab::fit {

namespace {

[[noreturn]] void unusable_file(const std::filesystem::path& path, const std::string& reason) {
  throw InputError("FILE", path.string() + ": " + reason,
                   "a file written by scatterlab simulate with the radiance tally");
}

std::size_t product(const std::vector<std::size_t>& shape) {
  std::size_t values = 1;
  for (const std::size_t extent : shape) values *= extent;
  return values;
}

// E = integral of L w d omega over the bins, for files without the flux tally.
std::vector<double> flux_from_radiance(const RadianceLobes& lobes, const LobeGrid& grid) {
  std::vector<double> flux;
  for (std::size_t r = 0; r < lobes.r_bins(); ++r) {
    for (std::size_t z = 0; z < lobes.z_bins(); ++z) {
      const LobeData data = lobes.lobe(r, z);
      Eigen::Vector3d e = Eigen::Vector3d::Zero();
      for (std::size_t bin = 0; bin < grid.size(); ++bin) {
        if (std::isfinite(data.mean[bin])) {
          e += grid.solid_angle(bin) * data.mean[bin] * grid.centre(bin);
        }
      }
      if (grid.phi_folded()) e.y() = 0.0;  // the mirror image cancels E_phi
      flux.insert(flux.end(), {e.x(), e.y(), e.z()});
    }
  }
  return flux;
}

std::optional<Eigen::Vector3d> flux_axis(const LobeData& data) {
  const double norm = data.flux.norm();
  if (!(norm > 0.0) || !std::isfinite(norm)) return std::nullopt;
  return Eigen::Vector3d(data.flux / norm);
}

// The start with the lowest cost among the candidates (lobe_fits_file.hpp, fit_lobes).
LobeParameters best_start(LobeModel model, const LobeGrid& grid, const LobeObservations& o,
                          const std::vector<LobeParameters>& candidates) {
  std::size_t best = 0;
  double best_cost = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const double cost = fit_cost(model, grid, o, candidates[i]);
    if (cost < best_cost) best = i, best_cost = cost;
  }
  return candidates[best];
}

using BinFits = std::array<std::optional<LobeFit>, kAllLobeModels.size()>;

const LobeFit* find_fit(const BinFits& fits, LobeModel model) {
  const auto& fit = fits[static_cast<std::size_t>(model)];
  return fit && usable(fit->status) ? &*fit : nullptr;
}

// The model whose solution is a point of `model`'s parameter space (sg_free holds sg with p = E,
// dexp holds the paper's estimate, adexp holds dexp at eta = 0, adexp_ridge holds adexp at
// c = 0), and for asg the model it is started from (sg_free, through asg_from_sg).
std::optional<LobeModel> subset_of(LobeModel model) {
  switch (model) {
    case LobeModel::sg_free:
      return LobeModel::sg;
    case LobeModel::dexp:
      return LobeModel::dexp_paper;
    case LobeModel::adexp:
      return LobeModel::dexp;
    case LobeModel::asg:
      return LobeModel::sg_free;
    case LobeModel::adexp_ridge:
      return LobeModel::adexp;
    case LobeModel::adexp2_ridge:
      return LobeModel::adexp_ridge;
    case LobeModel::sg:
    case LobeModel::dexp_paper:
      break;
  }
  return std::nullopt;
}

// The starting points of one model in one bin: from the data alone, from the subset's solution
// in this bin, and from the neighbour's solution (the previous z in the column).
// The data-only estimates of one bin, each computed once for all the models that use it.
struct Estimates {
  LobeParameters double_exponential;
  std::optional<LobeParameters> sg_on_axis, sg_on_peak;  // SG about E (or the peak), and the peak
};

std::vector<LobeParameters> candidates(LobeModel model, const LobeGrid& grid,
                                       const LobeObservations& o, const Eigen::Vector3d& e_axis,
                                       Estimates& estimates, const BinFits& previous,
                                       const BinFits& current) {
  std::vector<LobeParameters> starts;
  switch (model) {
    case LobeModel::sg:
    case LobeModel::sg_free:
      if (!estimates.sg_on_axis)
        estimates.sg_on_axis = spherical_gaussian_estimate(grid, o, e_axis);
      starts.push_back(*estimates.sg_on_axis);
      break;
    case LobeModel::dexp_paper:
    case LobeModel::dexp:
    case LobeModel::adexp:
      starts.push_back(estimates.double_exponential);
      break;
    case LobeModel::asg:
      if (!estimates.sg_on_peak) {
        estimates.sg_on_peak =
            spherical_gaussian_estimate(grid, o, estimates.double_exponential.axis);
      }
      starts.push_back(asg_from_sg(*estimates.sg_on_peak));
      break;
    case LobeModel::adexp_ridge:
    case LobeModel::adexp2_ridge:
      break;
  }
  if (model == LobeModel::dexp_paper) return starts;  // the paper's estimate, as printed
  if (const auto subset = subset_of(model)) {
    if (const LobeFit* fit = find_fit(current, *subset)) {
      LobeParameters start = fit->parameters;
      if (model == LobeModel::adexp) start.shape[3] = 0.0;
      if (model == LobeModel::asg) start = asg_from_sg(start);
      if (model == LobeModel::adexp_ridge) {
        starts.push_back(ridge_from_adexp(grid, o, start, false));
        start = ridge_from_adexp(grid, o, start, true);
      }
      if (model == LobeModel::adexp2_ridge) {
        for (const LobeParameters& second : second_lobe_starts(start)) starts.push_back(second);
      } else {
        starts.push_back(start);
      }
    }
  }
  if (const LobeFit* neighbour = find_fit(previous, model)) {
    LobeParameters start = neighbour->parameters;
    if (model == LobeModel::sg) start.axis = e_axis;  // p stays E / |E| of this bin
    starts.push_back(start);
  }
  return starts;
}

// All models of one spatial bin, in the order of kAllLobeModels so that each can start from
// the one it contains.
void fit_bin(const LobeGrid& grid, const LobeData& data, const std::vector<bool>& wanted,
             const FitOptions& options, const BinFits& previous, BinFits& current,
             std::size_t& attempted, std::array<double, kAllLobeModels.size()>& seconds) {
  const LobeObservations o = observe(grid, data, options);
  const std::optional<Eigen::Vector3d> e_axis = flux_axis(data);
  std::optional<Estimates> estimates;  // once the bin is known to be fitted
  for (const LobeModel model : kAllLobeModels) {
    const auto index = static_cast<std::size_t>(model);
    if (!wanted[index]) continue;
    LobeFit skipped;
    if (o.status != FitStatus::converged) {
      skipped.status = o.status;
      skipped.message = o.message;
      current[index] = skipped;
      continue;
    }
    if (model == LobeModel::sg && !e_axis) {
      skipped.status = FitStatus::no_axis;
      skipped.message = "vector irradiance E is zero: no axis for the SG";
      current[index] = skipped;
      continue;
    }
    if (!estimates) estimates = Estimates{double_exponential_estimate(grid, o), {}, {}};
    const Eigen::Vector3d axis = e_axis.value_or(estimates->double_exponential.axis);
    const std::vector<LobeParameters> starts =
        candidates(model, grid, o, axis, *estimates, previous, current);
    if (starts.empty()) continue;  // adexp_ridge without an adexp fit in this bin
    const auto start = std::chrono::steady_clock::now();
    if (model == LobeModel::adexp2_ridge) {
      // Its starts differ in kind (where the second lobe begins: faint, tilted, or as in the
      // previous z bin), not only in cost, and the lowest start cost is rarely the best end
      // (on the 1e8-photon beam: 79 % of bins within 2x the noise from the faint start alone,
      // 90 % from the tilted one, 96 % from all three). Each is solved; the lowest chi-square
      // is kept.
      std::optional<LobeFit> best;
      for (const LobeParameters& s : starts) {
        ++attempted;
        LobeFit fit = fit_lobe(model, grid, data, o, s, options);
        if (!best || (usable(fit.status) && (!usable(best->status) || fit.cost < best->cost))) {
          best = std::move(fit);
        }
      }
      current[index] = *best;
    } else {
      if (model != LobeModel::dexp_paper) ++attempted;
      current[index] = fit_lobe(model, grid, data, o, best_start(model, grid, o, starts), options);
    }
    seconds[index] +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
}

std::string join(const std::vector<std::string>& parts) {
  std::string text;
  for (const std::string& part : parts) text += (text.empty() ? "" : ",") + part;
  return text;
}

double percentile(std::vector<double> values, double fraction) {
  if (values.empty()) return -1.0;
  std::sort(values.begin(), values.end());
  const auto rank =
      static_cast<std::size_t>(std::ceil(fraction * static_cast<double>(values.size())));
  return values[std::clamp<std::size_t>(rank, 1, values.size()) - 1];
}

const ModelFits* find_model(const LobeFitRun& run, LobeModel model) {
  for (const ModelFits& fits : run.models) {
    if (fits.model == model) return &fits;
  }
  return nullptr;
}

// The radiance's mean and standard error are held whole while its bins are fitted, with the
// flux beside them and a model's values for a bin per thread: three arrays of the radiance at
// most. Checked from the declared shape before either is read (core/memory_budget.hpp).
void check_fit_memory(const hdf5::Dataset& radiance) {
  const std::uint64_t values = value_count(radiance.shape());
  MemoryEstimate need;
  need.add_doubles(fmt::format("radiance arrays of {} values", values), values, 3);
  check_memory(need, radiance.location(), "a smaller radiance tally");
}

}  // namespace

LobeData RadianceLobes::lobe(std::size_t r, std::size_t z) const {
  const std::size_t bin = r * z_bins() + z;
  LobeData data;
  data.mean = std::span<const double>(mean).subspan(bin * directions(), directions());
  data.stderr_of_mean =
      std::span<const double>(stderr_of_mean).subspan(bin * directions(), directions());
  data.flux = Eigen::Vector3d(flux[3 * bin], flux[3 * bin + 1], flux[3 * bin + 2]);
  return data;
}

RadianceLobes read_radiance_lobes(const std::filesystem::path& path) {
  read_file_header(path);  // InputError("FILE", ...) unless a readable scatterlab file
  RadianceLobes lobes;
  lobes.path = path;
  try {
    const hdf5::File file = hdf5::File::open_read_only(path);
    const hdf5::Group& root = file.root();
    if (!root.has_member("tallies/radiance/mean") || !root.has_member("tallies/radiance/stderr")) {
      unusable_file(path, "no radiance tally (/tallies/radiance); run simulate with it");
    }
    if (root.has_member("parameters")) {
      const hdf5::Group parameters = root.open_group("parameters");
      if (parameters.has_attribute("albedo"))
        lobes.albedo = parameters.read_double_attribute("albedo");
      if (parameters.has_attribute("g")) lobes.g = parameters.read_double_attribute("g");
    }
    const hdf5::Group grid = root.open_group("grid");
    lobes.phi_folded = grid.has_attribute("phi_folded") && grid.read_int64_attribute("phi_folded");
    lobes.r_edges = grid.read_dataset("r").values;
    lobes.z_edges = grid.read_dataset("z").values;
    lobes.theta_edges = grid.read_dataset("theta").values;
    lobes.phi_edges = grid.read_dataset("phi").values;
    try {
      LobeGrid(lobes.theta_edges, lobes.phi_edges, lobes.phi_folded, 1);  // the angles' ranges
    } catch (const std::invalid_argument& angles) {
      unusable_file(path, fmt::format("its direction grid is not one lobes are fitted on: {}",
                                      angles.what()));
    }
    check_fit_memory(root.open_dataset("tallies/radiance/mean"));
    hdf5::Array mean = root.read_dataset("tallies/radiance/mean");
    hdf5::Array error = root.read_dataset("tallies/radiance/stderr");
    const std::vector<std::size_t> expected = {lobes.r_edges.size() - 1, lobes.z_edges.size() - 1,
                                               lobes.theta_edges.size() - 1,
                                               lobes.phi_edges.size() - 1};
    if (mean.shape != expected || error.shape != expected) {
      unusable_file(path,
                    "radiance mean and stderr must have the shape of the grid [r, z, theta, phi]");
    }
    lobes.mean = std::move(mean.values);
    lobes.stderr_of_mean = std::move(error.values);
    if (root.has_member("tallies/flux/mean")) {
      const hdf5::Array flux = root.read_dataset("tallies/flux/mean");
      if (flux.shape != std::vector<std::size_t>{expected[0], expected[1], 2}) {
        unusable_file(path, "flux mean must have shape [r, z, 2]");
      }
      for (std::size_t i = 0; i < product(flux.shape); i += 2) {
        lobes.flux.insert(lobes.flux.end(), {flux.values[i], 0.0, flux.values[i + 1]});
      }
      lobes.flux_from_tally = true;
    }
  } catch (const InputError&) {
    throw;
  } catch (const std::runtime_error& failure) {
    unusable_file(path, failure.what());
  }
  if (!lobes.flux_from_tally) {
    lobes.flux.assign(3 * lobes.r_bins() * lobes.z_bins(), 0.0);  // lobe() reads it below
    lobes.flux = flux_from_radiance(
        lobes, LobeGrid(lobes.theta_edges, lobes.phi_edges, lobes.phi_folded, 1));
  }
  return lobes;
}

LobeFitRun fit_lobes(const RadianceLobes& lobes, const LobeGrid& grid,
                     const std::vector<LobeModel>& models, const FitOptions& options, int threads,
                     const WorkProgress& progress) {
  if (grid.size() != lobes.directions()) {
    throw std::invalid_argument("fit_lobes: the angular grid does not match the radiance tally");
  }
  // A model asked for brings the models it starts from (subset_of), so that it can never end
  // with a larger chi-square than them; only the models asked for are reported.
  std::vector<bool> wanted(kAllLobeModels.size(), false);
  for (LobeModel model : models) {
    wanted[static_cast<std::size_t>(model)] = true;
    while (const auto subset = subset_of(model)) {
      model = *subset;
      wanted[static_cast<std::size_t>(model)] = true;
    }
  }
  const std::size_t nr = lobes.r_bins(), nz = lobes.z_bins();
  // fits[model][r * nz + z]
  std::vector<std::vector<LobeFit>> fits(kAllLobeModels.size(), std::vector<LobeFit>(nr * nz));

  LobeFitRun run;
  run.threads = threads > 0 ? threads : omp_get_max_threads();
  std::size_t attempted = 0;
  std::array<double, kAllLobeModels.size()> seconds{};
  const auto start = std::chrono::steady_clock::now();
  std::atomic<std::uint64_t> bins_fitted{0};
#pragma omp parallel for schedule(dynamic, 1) num_threads(run.threads) reduction(+ : attempted)
  for (std::size_t r = 0; r < nr; ++r) {
    BinFits previous, current;
    std::array<double, kAllLobeModels.size()> column_seconds{};
    for (std::size_t z = 0; z < nz; ++z) {
      current.fill(std::nullopt);
      fit_bin(grid, lobes.lobe(r, z), wanted, options, previous, current, attempted,
              column_seconds);
      for (std::size_t m = 0; m < current.size(); ++m) {
        if (current[m]) fits[m][r * nz + z] = *current[m];
      }
      std::swap(previous, current);
      const std::uint64_t fitted = ++bins_fitted;
      if (progress && omp_get_thread_num() == 0) progress(fitted, nr * nz);
    }
#pragma omp critical(scatterlab_fit_seconds)
    for (std::size_t m = 0; m < seconds.size(); ++m) seconds[m] += column_seconds[m];
  }
  run.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.attempted_fits = attempted;
  for (const LobeModel model : models) {
    const auto index = static_cast<std::size_t>(model);
    run.models.push_back({model, std::move(fits[index]), seconds[index]});
  }
  return run;
}

void write_fits(const RadianceLobes& lobes, const LobeGrid& grid, const LobeFitRun& run,
                const FitOptions& options) {
  AtomicOutput output(lobes.path);
  std::filesystem::copy_file(lobes.path, output.temporary_path());
  {
    hdf5::File file = hdf5::File::open_read_write(output.temporary_path());
    if (!file.root().has_member("fits")) file.root().create_group("fits");
    hdf5::Group fits = file.root().open_group("fits");
    const std::size_t nr = lobes.r_bins(), nz = lobes.z_bins();
    for (const ModelFits& model : run.models) {
      const std::string name = to_string(model.model);
      if (fits.has_member(name)) fits.remove_member(name);
      hdf5::Group group = fits.create_group(name);
      group.write_string_attribute("model", describe(model.model));
      group.write_string_attribute(
          "objective",
          "chi-square on L: sum_i ((<model>_i - L_i) / sigma_i)^2 over every direction, <model>_i "
          "the model averaged over angular bin i, sigma_i = max(stderr_i, Q / Omega_i) with "
          "Q = median of stderr^2 Omega / L (one event's radiance times its solid angle)");
      group.write_double_attribute("max_relative_stderr", options.max_relative_stderr);
      group.write_int64_attribute("min_directions",
                                  static_cast<std::int64_t>(options.min_directions));
      group.write_int64_attribute("quadrature_order", grid.quadrature_order());
      group.write_string_attribute("axis_frame", "p = (p_r, p_phi, p_z) in (e_r, e_phi, e_z)");

      const std::vector<std::string> names = parameter_names(model.model);
      std::vector<double> params, error, plane, noise, chi2;
      std::vector<std::int32_t> status;
      for (const LobeFit& fit : model.fits) {
        const bool ok = usable(fit.status);
        const std::vector<double> values = reported_parameters(model.model, fit.parameters);
        for (const double value : values)
          params.push_back(ok && std::isfinite(value) ? value : 0.0);
        error.push_back(ok ? fit.error_sphere : -1.0);
        plane.push_back(ok ? fit.error_plane : -1.0);
        noise.push_back(ok ? fit.noise : -1.0);
        chi2.push_back(ok ? fit.chi2_dof : -1.0);
        status.push_back(static_cast<std::int32_t>(fit.status));
      }
      hdf5::Dataset parameters = group.write_dataset("params", params, {nr, nz, names.size()});
      parameters.write_string_attribute("names", join(names));
      parameters.write_string_attribute("description",
                                        "each (r, z) bin's fitted parameters, in the order of "
                                        "attr names; 0 where not fitted (see status)");
      group.write_dataset("error", error, {nr, nz})
          .write_string_attribute("description",
                                  "relative L1 error over the sphere, sum Omega |model - L| / "
                                  "sum Omega L over every direction; -1 where not fitted");
      group.write_dataset("error_plane", plane, {nr, nz})
          .write_string_attribute("description",
                                  "the same over the bins on the phi = 0 / phi = pi plane; -1 "
                                  "where not fitted");
      group.write_dataset("noise", noise, {nr, nz})
          .write_string_attribute("description",
                                  "sqrt(2/pi) sum Omega stderr / sum Omega L: the error an exact "
                                  "model would show; -1 where not fitted");
      group.write_dataset("chi2_dof", chi2, {nr, nz})
          .write_string_attribute("description",
                                  "chi-square / (directions - free parameters); -1 where not "
                                  "fitted");
      group.write_dataset("status", status, {nr, nz})
          .write_string_attribute("legend", fit_status_legend());
    }
    file.close();
  }
  output.commit();
}

std::vector<std::string> fits_csv_header(const LobeFitRun& run) {
  std::vector<std::string> header = {"r_index", "z_index", "r", "z"};
  for (const ModelFits& model : run.models) {
    const std::string name = to_string(model.model);
    for (const char* column : {"status", "error", "error_plane", "noise", "chi2_dof"}) {
      header.push_back(name + "_" + column);
    }
    for (const std::string& parameter : parameter_names(model.model)) {
      header.push_back(name + "_" + parameter);
    }
  }
  return header;
}

std::vector<std::vector<std::string>> fits_csv_rows(const RadianceLobes& lobes,
                                                    const LobeFitRun& run) {
  std::vector<std::vector<std::string>> rows;
  for (std::size_t r = 0; r < lobes.r_bins(); ++r) {
    for (std::size_t z = 0; z < lobes.z_bins(); ++z) {
      std::vector<std::string> row = {
          std::to_string(r), std::to_string(z),
          fmt::format("{:.6g}", 0.5 * (lobes.r_edges[r] + lobes.r_edges[r + 1])),
          fmt::format("{:.6g}", 0.5 * (lobes.z_edges[z] + lobes.z_edges[z + 1]))};
      for (const ModelFits& model : run.models) {
        const LobeFit& fit = model.fits[r * lobes.z_bins() + z];
        const bool ok = usable(fit.status);
        row.push_back(to_string(fit.status));
        for (const double value : {fit.error_sphere, fit.error_plane, fit.noise, fit.chi2_dof}) {
          row.push_back(fmt::format("{:.6g}", ok ? value : -1.0));
        }
        for (const double value : reported_parameters(model.model, fit.parameters)) {
          row.push_back(fmt::format("{:.8g}", ok && std::isfinite(value) ? value : 0.0));
        }
      }
      rows.push_back(std::move(row));
    }
  }
  return rows;
}

std::string join_csv(const std::vector<std::string>& fields) {
  return join(fields);
}

FileFit fit_file(const std::filesystem::path& path, const std::filesystem::path& csv,
                 const std::vector<LobeModel>& models, const FitOptions& options, int quadrature,
                 int threads, const WorkProgress& progress) {
  if (quadrature < 1 || quadrature > 8) {
    throw InputError("quadrature", std::to_string(quadrature), "an integer in [1, 8]");
  }
  FileFit fit;
  fit.lobes = read_radiance_lobes(path);
  const LobeGrid grid(fit.lobes.theta_edges, fit.lobes.phi_edges, fit.lobes.phi_folded, quadrature);
  fit.theta_bins = grid.theta_bins();
  fit.phi_bins = grid.phi_bins();
  fit.run = fit_lobes(fit.lobes, grid, models, options, threads, progress);
  write_fits_csv(csv, fit.lobes, fit.run);
  write_fits(fit.lobes, grid, fit.run, options);
  return fit;
}

std::filesystem::path default_fits_csv(const std::filesystem::path& file) {
  std::filesystem::path csv = file;
  csv.replace_extension();
  csv += "-fits.csv";
  return csv;
}

void write_fits_csv(const std::filesystem::path& path, const RadianceLobes& lobes,
                    const LobeFitRun& run) {
  write_text_file(path, [&lobes, &run](std::ostream& csv) {
    csv << join(fits_csv_header(run)) << '\n';
    for (const auto& row : fits_csv_rows(lobes, run)) csv << join(row) << '\n';
  });
}

namespace {

// Counts the bins where both fitted in which `a` ends worse than `b`, by chi^2 and by the L1
// error.
void count_worse(const ModelFits* a, const ModelFits* b, SupersetCheck& check) {
  if (!a || !b) return;
  check.superset = a->model;
  check.subset = b->model;
  for (std::size_t i = 0; i < a->fits.size(); ++i) {
    const LobeFit &x = a->fits[i], &y = b->fits[i];
    if (!usable(x.status) || !usable(y.status)) continue;
    ++check.bins;
    check.worse_error += x.error_sphere > y.error_sphere * (1.0 + 1e-9);
    check.worse_chi2 += x.cost > y.cost * (1.0 + 1e-9);  // the same data and sigma: comparable
  }
}

}  // namespace

LobeFitSummary summarize(const LobeFitRun& run) {
  LobeFitSummary summary;
  for (const ModelFits& model : run.models) {
    ModelFitSummary s{model.model};
    s.seconds = model.seconds;
    std::vector<double> errors, planes, noises, ratios, chi2;
    for (const LobeFit& fit : model.fits) {
      if (usable(fit.status)) {
        ++s.fitted;
        errors.push_back(fit.error_sphere);
        if (fit.error_plane >= 0.0) planes.push_back(fit.error_plane);
        noises.push_back(fit.noise);
        if (fit.noise > 0.0) ratios.push_back(fit.error_sphere / fit.noise);
        chi2.push_back(fit.chi2_dof);
        s.converged += fit.status == FitStatus::converged;
        s.mean_iterations += fit.iterations;
      } else if (skipped(fit.status)) {
        ++s.skipped;
      } else {
        ++s.failed;
      }
    }
    if (s.fitted > 0) s.mean_iterations /= static_cast<double>(s.fitted);
    s.median_error = percentile(errors, 0.5);
    s.p90_error = percentile(errors, 0.9);
    s.median_plane = percentile(planes, 0.5);
    s.p90_plane = percentile(planes, 0.9);
    s.median_noise = percentile(noises, 0.5);
    s.median_ratio = percentile(ratios, 0.5);
    s.p90_ratio = percentile(ratios, 0.9);
    s.median_chi2_dof = percentile(chi2, 0.5);
    s.p90_chi2_dof = percentile(chi2, 0.9);
    std::size_t within = 0;
    for (const double ratio : ratios) within += ratio <= 2.0;
    s.within_twice_noise =
        ratios.empty() ? -1.0 : static_cast<double>(within) / static_cast<double>(ratios.size());
    summary.models.push_back(s);
  }
  const ModelFits* sg = find_model(run, LobeModel::sg);
  const ModelFits* dexp = find_model(run, LobeModel::dexp);
  const ModelFits* adexp = find_model(run, LobeModel::adexp);
  if (sg && dexp) {
    std::size_t both = 0, wins = 0, all = 0, adexp_wins = 0;
    for (std::size_t i = 0; i < sg->fits.size(); ++i) {
      const LobeFit &a = sg->fits[i], &b = dexp->fits[i];
      if (!usable(a.status) || !usable(b.status)) continue;
      ++both;
      wins += b.error_sphere < a.error_sphere;
      if (adexp && usable(adexp->fits[i].status)) {
        ++all;
        adexp_wins += adexp->fits[i].error_sphere < std::min(a.error_sphere, b.error_sphere);
      }
    }
    if (both > 0) summary.dexp_beats_sg = static_cast<double>(wins) / static_cast<double>(both);
    if (adexp && all > 0) {
      summary.adexp_beats_sg_and_dexp = static_cast<double>(adexp_wins) / static_cast<double>(all);
    }
  }
  for (const ModelFits& model : run.models) {
    const std::optional<LobeModel> subset = subset_of(model.model);
    if (!subset || model.model == LobeModel::asg) continue;  // asg does not contain sg_free
    SupersetCheck check;
    count_worse(&model, find_model(run, *subset), check);
    if (check.bins > 0) summary.supersets.push_back(check);
  }
  summary.fits_per_second =
      run.wall_seconds > 0.0 ? static_cast<double>(run.attempted_fits) / run.wall_seconds : 0.0;
  return summary;
}

std::string describe(const LobeFitSummary& summary, const LobeFitRun& run) {
  std::string text =
      "  model       fitted conv skip fail | error: median    p90 | plane: median    p90 | "
      "noise: median | error/noise: median   p90  <=2x | chi2/dof: median    p90 | seconds "
      "iterations\n";
  for (const ModelFitSummary& s : summary.models) {
    text += fmt::format(
        "  {:<10} {:>7} {:>4} {:>4} {:>4} | {:>13.4f} {:>6.4f} | {:>13.4f} {:>6.4f} | {:>13.4f} | "
        "{:>19.2f} {:>5.2f} {:>4.0f}% | {:>16.2f} {:>6.2f} | {:>7.1f} {:>10.1f}\n",
        to_string(s.model), s.fitted, s.converged, s.skipped, s.failed, s.median_error, s.p90_error,
        s.median_plane, s.p90_plane, s.median_noise, s.median_ratio, s.p90_ratio,
        100.0 * s.within_twice_noise, s.median_chi2_dof, s.p90_chi2_dof, s.seconds,
        s.mean_iterations);
  }
  text +=
      "  (relative L1 errors over the sphere and the phi = 0 plane, over every direction; "
      "noise: what an exact\n   model would show; <=2x: bins within twice the noise; "
      "fitted by chi-square on L;\n   seconds: thread time spent on the model's fits; iterations: "
      "Levenberg-Marquardt iterations per fit)\n";
  if (summary.dexp_beats_sg >= 0.0) {
    text += fmt::format("  dexp beats sg in {:.1f} % of bins\n", 100.0 * summary.dexp_beats_sg);
  }
  if (summary.adexp_beats_sg_and_dexp >= 0.0) {
    text += fmt::format("  adexp beats sg and dexp in {:.1f} % of bins\n",
                        100.0 * summary.adexp_beats_sg_and_dexp);
  }
  for (const SupersetCheck& c : summary.supersets) {
    text += fmt::format(
        "  {} worse than {} (which it contains) in {} of {} bins by chi2, {} by "
        "the L1 error\n",
        to_string(c.superset), to_string(c.subset), c.worse_chi2, c.bins, c.worse_error);
  }
  text += fmt::format("  {} fits in {:.2f} s on {} thread{}: {:.0f} fits/s\n", run.attempted_fits,
                      run.wall_seconds, run.threads, run.threads == 1 ? "" : "s",
                      summary.fits_per_second);
  return text;
}

}  // namespace scatterlab::fit
