#include "scatterlab/validate/validation_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "scatterlab/core/error.hpp"
#include "scatterlab/io/atomic_output.hpp"
#include "scatterlab/io/output_plan.hpp"
#include "scatterlab/io/plot.hpp"

namespace scatterlab {
namespace {

std::vector<double> centres(const std::vector<double>& lo, const std::vector<double>& hi) {
  std::vector<double> c(lo.size());
  for (std::size_t i = 0; i < lo.size(); ++i) c[i] = 0.5 * (lo[i] + hi[i]);
  return c;
}

// rho_c^2 times each value (d'Eon & Irving's r^2 phi(r) curves).
std::vector<double> times_rho2(const std::vector<double>& rho, const std::vector<double>& v) {
  std::vector<double> out(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) out[i] = rho[i] * rho[i] * v[i];
  return out;
}

std::string nan_or(double v) {
  return std::isnan(v) ? "nan" : fmt::format("{:.6g}", v);
}

// A model's name in a legend: what it is and where it is published (models/dipole.hpp,
// models/quantized_diffusion.hpp, models/photon_beam_diffusion.hpp, models/grosjean_beam.hpp).
std::string display_name(const std::string& model) {
  const std::string sum = "+single_scatter";
  if (model.ends_with(sum)) {
    return display_name(model.substr(0, model.size() - sum.size())) + " + exact single scattering";
  }
  if (model == "dipole") return "classical dipole (Jensen et al. 2001)";
  if (model == "better_dipole") return "better dipole (d'Eon 2012)";
  if (model == "quantized_diffusion") return "quantized diffusion (d'Eon & Irving 2011)";
  if (model == "photon_beam_diffusion") return "photon beam diffusion (Habel et al. 2013)";
  if (model == "scatterlab_grosjean_beam") return "Grosjean beam (scatterlab)";
  if (model == "single_scatter") return "exact single scattering";
  if (model == "measured") return "on the half-space Monte Carlo's own R_d(r)";
  return model;
}

// A model's style key (io/plot.hpp): the same colour and line in every figure.
std::string style_key(const std::string& model) {
  const std::string prefix = "scatterlab_";
  return model.starts_with(prefix) ? model.substr(prefix.size()) : model;
}

constexpr const char* monte_carlo_name = "Monte Carlo ±1σ";
constexpr double degree_in_radians = std::numbers::pi / 180.0;

// A medium of the transport specs, in its own length unit, for a plot title.
std::string medium_text(const Medium& m) {
  return fmt::format("albedo {:.5g}, $\\sigma_t$ = {:.4g} {}$^{{-1}}$, $g$ = {:.4g}", m.albedo,
                     m.sigma_t, m.length_unit, m.g);
}

// The medium, short enough for a plot title's line (matplotlib mathtext), its values rounded:
// 1 - 0.99 is 0.010000000000000009 in binary.
std::string title_of(const HalfSpaceMedium& medium) {
  return fmt::format(
      "$\\sigma_a$ = {:.4g}, $\\sigma_s$ = {:.4g} mfp$^{{-1}}$, $g$ = {:.4g}, $\\eta$ = {:.4g}",
      medium.sigma_a, medium.sigma_s, medium.g, medium.eta);
}

}  // namespace

std::vector<std::filesystem::path> write_point_source_report(
    const std::vector<PointSourceComparison>& comparisons, const std::filesystem::path& directory) {
  make_output_directory(directory, "--out");
  std::vector<std::filesystem::path> written;
  const auto shells = directory / "deon_point_source.csv";
  write_text_file(shells, [&](std::ostream& out) {
    out << "# Isotropic point source, infinite medium, g = 0: shell-averaged fluence in mfp^-2 per "
           "unit source power (Monte Carlo mean and standard error, exact transport, classical "
           "diffusion, Grosjean)\n";
    out << "albedo,rho_lo_mfp,rho_hi_mfp,monte_carlo,monte_carlo_stderr,exact,diffusion,grosjean\n";
    for (const PointSourceComparison& c : comparisons) {
      for (std::size_t i = 0; i < c.exact.size(); ++i) {
        out << fmt::format("{},{},{},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g}\n", c.albedo, c.rho_lo[i],
                           c.rho_hi[i], c.monte_carlo[i], c.monte_carlo_stderr[i], c.exact[i],
                           c.diffusion[i], c.grosjean[i]);
      }
    }
  });
  written.push_back(shells);
  const auto errors = directory / "deon_errors.csv";
  write_text_file(errors, [&](std::ostream& out) {
    out << "# Mean relative error |model - exact| / exact of the shell averages, near (rho < 1 "
           "mfp) "
           "and far (1 <= rho < rho_max); Monte Carlo over shells expecting >= 100 collisions\n";
    out << "albedo,model,near_relative_error,far_relative_error,max_abs_z,within_3_sigma,"
           "compared_shells\n";
    for (const PointSourceComparison& c : comparisons) {
      out << fmt::format("{},monte_carlo,{:.6g},{:.6g},{:.3f},{:.4f},{}\n", c.albedo,
                         c.monte_carlo_error.near, c.monte_carlo_error.far, c.max_abs_z,
                         c.within_3_sigma, c.compared_shells);
      out << fmt::format("{},diffusion,{:.6g},{:.6g},,,\n", c.albedo, c.diffusion_error.near,
                         c.diffusion_error.far);
      out << fmt::format("{},grosjean,{:.6g},{:.6g},,,\n", c.albedo, c.grosjean_error.near,
                         c.grosjean_error.far);
    }
  });
  written.push_back(errors);

  std::vector<PlotFile> figures;
  for (const PointSourceComparison& c : comparisons) {
    const auto rho = centres(c.rho_lo, c.rho_hi);
    for (const AxisScale scale : {AxisScale::linear, AxisScale::log}) {
      LinePlot plot;
      plot.title = fmt::format(
          "Isotropic point source in an infinite medium, albedo {:g}, isotropic scattering",
          c.albedo);
      plot.x_label = "distance from the source $r$ (mfp)";
      plot.y_label = "$r^2\\,\\phi(r)$ (per unit source power)";
      plot.y_scale = scale;
      std::vector<double> mc_error = times_rho2(rho, c.monte_carlo_stderr);
      plot.series = {
          {monte_carlo_name, rho, times_rho2(rho, c.monte_carlo), mc_error, true, "monte_carlo"},
          {"exact transport", rho, times_rho2(rho, c.exact), {}, false, "exact"},
          {"classical diffusion", rho, times_rho2(rho, c.diffusion), {}, false, "diffusion"},
          {"Grosjean (1956)", rho, times_rho2(rho, c.grosjean), {}, false, "grosjean"},
      };
      const auto path =
          directory / fmt::format("deon_albedo_{}_{}.png", c.albedo, to_string(scale));
      figures.push_back({plot, path});
      written.push_back(path);
    }
  }
  // Every albedo on one axis, as d'Eon & Irving 2011 Fig. 2 draws them: the exact curve and the
  // Monte Carlo points of an albedo in one colour (a key of the albedo's own, io/plot.hpp).
  LinePlot overview;
  overview.title =
      "Isotropic point source in an infinite medium, isotropic scattering, every albedo:\n"
      "lines exact transport, points Monte Carlo ±1σ";
  overview.x_label = "distance from the source $r$ (mfp)";
  overview.y_label = "$r^2\\,\\phi(r)$ (per unit source power)";
  overview.y_scale = AxisScale::log;
  for (const PointSourceComparison& c : comparisons) {
    const auto rho = centres(c.rho_lo, c.rho_hi);
    const std::string key = fmt::format("albedo {:g}", c.albedo);
    overview.series.push_back({key, rho, times_rho2(rho, c.exact), {}, false, key});
    overview.series.push_back({"", rho, times_rho2(rho, c.monte_carlo),
                               times_rho2(rho, c.monte_carlo_stderr), true, key});
  }
  const auto overview_path = directory / "deon_all_albedos_log.png";
  figures.push_back({overview, overview_path});
  written.push_back(overview_path);
  write_pngs(figures);
  return written;
}

std::string point_source_error_table(const std::vector<PointSourceComparison>& comparisons) {
  std::string table =
      fmt::format("{:>7} | {:>21} | {:>21} | {:>21} | {:>22}\n", "albedo", "diffusion near / far",
                  "Grosjean near / far", "Monte Carlo near/far", "MC vs exact: max|z|, <3σ");
  for (const PointSourceComparison& c : comparisons) {
    table += fmt::format(
        "{:>7} | {:>9.2f}% / {:>7.2f}% | {:>9.2f}% / {:>7.2f}% | {:>9.3f}% / {:>6.3f}% | {:>8.2f}, "
        "{:>5.1f}% of {}\n",
        c.albedo, 100 * c.diffusion_error.near, 100 * c.diffusion_error.far,
        100 * c.grosjean_error.near, 100 * c.grosjean_error.far, 100 * c.monte_carlo_error.near,
        100 * c.monte_carlo_error.far, c.max_abs_z, 100 * c.within_3_sigma, c.compared_shells);
  }
  return table;
}

std::vector<std::filesystem::path> write_half_space_report(const HalfSpaceComparison& c,
                                                           const std::filesystem::path& directory,
                                                           const std::string& stem) {
  make_output_directory(directory, "--out");
  std::vector<std::filesystem::path> written;
  const std::size_t nr = c.r_edges.size() - 1;
  const std::size_t nz = c.z_edges.empty() ? 0 : c.z_edges.size() - 1;
  const auto medium_line = fmt::format(
      "sigma_a {:.4g}, sigma_s {:.4g}, g {:.4g}, eta {:.4g}, entry transmittance {:.4f}",
      c.medium.sigma_a, c.medium.sigma_s, c.medium.g, c.medium.eta, c.entry_transmittance);
  const std::string medium_title = title_of(c.medium);
  const ModelPart parts[] = {ModelPart::all, ModelPart::single, ModelPart::multiple};
  const auto part_name = [](ModelPart part) {
    const std::string suffix = tally_suffix(part);
    return suffix.empty() ? std::string("all") : suffix.substr(1);
  };

  const auto reflectance_csv = directory / (stem + "_reflectance.csv");
  write_text_file(reflectance_csv, [&](std::ostream& out) {
    out << "# Searchlight problem, " << medium_line
        << ": R_d annulus averages per unit area per unit incident power. Each model is held "
           "against the Monte Carlo part it models (its column [part]): all = single + "
           "multiple.\n# totals:";
    for (const ModelCurve& m : c.reflectance) {
      out << fmt::format(" {} [{}] R_dr = {:.6g} (error near {}, far {});", m.model,
                         part_name(m.part), m.total, nan_or(m.near_error), nan_or(m.far_error));
    }
    out << "\nr_lo,r_hi";
    for (const ModelPart part : parts) {
      if (c.reflectance_mc.contains(part)) {
        out << fmt::format(",monte_carlo_{0},monte_carlo_{0}_stderr", part_name(part));
      }
    }
    for (const ModelCurve& m : c.reflectance)
      out << "," << m.model << "[" << part_name(m.part) << "]";
    out << "\n";
    for (std::size_t i = 0; i < nr; ++i) {
      out << c.r_edges[i] << "," << c.r_edges[i + 1];
      for (const ModelPart part : parts) {
        const auto mc = c.reflectance_mc.find(part);
        if (mc != c.reflectance_mc.end()) {
          out << fmt::format(",{:.9g},{:.9g}", mc->second.mean[i], mc->second.stderr_of_mean[i]);
        }
      }
      for (const ModelCurve& m : c.reflectance) out << fmt::format(",{:.9g}", m.values[i]);
      out << "\n";
    }
  });
  written.push_back(reflectance_csv);

  std::vector<double> r(nr);
  for (std::size_t i = 0; i < nr; ++i) r[i] = 0.5 * (c.r_edges[i] + c.r_edges[i + 1]);
  const auto times_r = [&](const std::vector<double>& v) {
    std::vector<double> out(v.size());
    for (std::size_t i = 0; i < v.size(); ++i) out[i] = r[i] * v[i];
    return out;
  };
  // Bitterli §3.6.3: linear, log and sqrt y axes, and r R_d to damp the peak at the source; one
  // set per part, each model beside the Monte Carlo part it models.
  struct Mode {
    const char* name;
    AxisScale scale;
    bool times_r;
  };
  const auto part_title = [](ModelPart part) {
    switch (part) {
      case ModelPart::single:
        return "light scattered once";
      case ModelPart::multiple:
        return "light scattered at least twice";
      case ModelPart::all:
        return "all scattered light";
    }
    return "";
  };
  std::vector<PlotFile> figures;
  for (const ModelPart part : {ModelPart::multiple, ModelPart::all}) {
    for (const Mode mode :
         {Mode{"linear", AxisScale::linear, false}, Mode{"log", AxisScale::log, false},
          Mode{"sqrt", AxisScale::sqrt, false}, Mode{"rR", AxisScale::linear, true}}) {
      LinePlot plot;
      plot.title =
          fmt::format("Searchlight, diffuse reflectance of {}\n{}", part_title(part), medium_title);
      plot.x_label = "distance from the beam $r$ (mfp)";
      plot.y_label = mode.times_r ? "$r\\,R_\\mathrm{d}(r)$ (mfp$^{-1}$ per unit incident power)"
                                  : "$R_\\mathrm{d}(r)$ (mfp$^{-2}$ per unit incident power)";
      plot.y_scale = mode.scale;
      const auto mc = c.reflectance_mc.find(part);
      if (mc != c.reflectance_mc.end()) {
        const MonteCarloCurve& m = mc->second;
        plot.series.push_back({monte_carlo_name, r, mode.times_r ? times_r(m.mean) : m.mean,
                               mode.times_r ? times_r(m.stderr_of_mean) : m.stderr_of_mean, true,
                               "monte_carlo"});
      }
      for (const ModelCurve& m : c.reflectance) {
        if (m.part != part) continue;
        plot.series.push_back({display_name(m.model),
                               r,
                               mode.times_r ? times_r(m.values) : m.values,
                               {},
                               false,
                               style_key(m.model)});
      }
      const auto path =
          directory / fmt::format("{}_reflectance_{}_{}.png", stem, part_name(part), mode.name);
      figures.push_back({plot, path});
      written.push_back(path);
    }
  }

  if (nz > 0) {
    const auto fluence_csv = directory / (stem + "_fluence.csv");
    write_text_file(fluence_csv, [&](std::ostream& out) {
      out << "# Searchlight problem, " << medium_line
          << ": fluence cell averages per unit incident power, each model beside the Monte "
             "Carlo part it models (its column [part])\nr_lo,r_hi,z_lo,z_hi";
      for (const ModelPart part : parts) {
        if (c.fluence_mc.contains(part)) {
          out << fmt::format(",monte_carlo_{0},monte_carlo_{0}_stderr", part_name(part));
        }
      }
      for (const ModelCurve& m : c.fluence)
        out << "," << m.model << "[" << part_name(m.part) << "]";
      out << "\n";
      for (std::size_t k = 0; k < nr * nz; ++k) {
        const std::size_t i = k / nz, j = k % nz;
        out << c.r_edges[i] << "," << c.r_edges[i + 1] << "," << c.z_edges[j] << ","
            << c.z_edges[j + 1];
        for (const ModelPart part : parts) {
          const auto mc = c.fluence_mc.find(part);
          if (mc != c.fluence_mc.end()) {
            out << fmt::format(",{:.9g},{:.9g}", mc->second.mean[k], mc->second.stderr_of_mean[k]);
          }
        }
        for (const ModelCurve& m : c.fluence) out << fmt::format(",{:.9g}", m.values[k]);
        out << "\n";
      }
    });
    written.push_back(fluence_csv);
    // phi along z in the innermost r bin, log scale, one plot per part.
    std::vector<double> z(nz);
    for (std::size_t j = 0; j < nz; ++j) z[j] = 0.5 * (c.z_edges[j] + c.z_edges[j + 1]);
    const auto first_row = [&](const std::vector<double>& v) {
      return std::vector<double>(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(nz));
    };
    for (const ModelPart part : {ModelPart::multiple, ModelPart::all}) {
      LinePlot plot;
      plot.title = fmt::format("Searchlight, fluence near the beam ($r$ < {:.3g} mfp) of {}\n{}",
                               c.r_edges[1], part_title(part), medium_title);
      plot.x_label = "depth $z$ (mfp)";
      plot.y_label = "$\\phi(r, z)$ (mfp$^{-2}$ per unit incident power)";
      plot.y_scale = AxisScale::log;
      const auto mc = c.fluence_mc.find(part);
      if (mc != c.fluence_mc.end()) {
        plot.series.push_back({monte_carlo_name, z, first_row(mc->second.mean),
                               first_row(mc->second.stderr_of_mean), true, "monte_carlo"});
      }
      for (const ModelCurve& m : c.fluence) {
        if (m.part == part) {
          plot.series.push_back(
              {display_name(m.model), z, first_row(m.values), {}, false, style_key(m.model)});
        }
      }
      if (plot.series.empty()) continue;
      const auto path = directory / fmt::format("{}_fluence_axis_{}.png", stem, part_name(part));
      figures.push_back({plot, path});
      written.push_back(path);
    }
  }
  write_pngs(figures);
  return written;
}

SingleScatterAgreement compare_single_scatter(const MonteCarloCurve& monte_carlo,
                                              const SingleScatterReflectance& exact,
                                              double monte_carlo_total,
                                              double monte_carlo_total_stderr) {
  SingleScatterAgreement agreement;
  double sum_z2 = 0.0;
  for (std::size_t i = 0; i < exact.mean.size(); ++i) {
    const double sigma = monte_carlo.stderr_of_mean[i];
    if (!(monte_carlo.mean[i] > 3.0 * sigma)) continue;
    const double z = (monte_carlo.mean[i] - exact.mean[i]) / sigma;
    agreement.max_abs_z = std::max(agreement.max_abs_z, std::abs(z));
    sum_z2 += z * z;
    ++agreement.rings;
  }
  agreement.mean_squared_z =
      agreement.rings > 0 ? sum_z2 / static_cast<double>(agreement.rings) : 0.0;
  agreement.total_z = (monte_carlo_total - exact.total) / monte_carlo_total_stderr;
  return agreement;
}

std::vector<std::filesystem::path> write_single_scatter_report(
    const std::vector<double>& r_edges, const MonteCarloCurve& mc,
    const SingleScatterReflectance& exact, const HalfSpaceMedium& medium,
    const std::filesystem::path& directory, const std::string& stem) {
  make_output_directory(directory, "--out");
  const std::size_t nr = r_edges.size() - 1;
  const auto csv = directory / fmt::format("{}_single_scatter.csv", stem);
  write_text_file(csv, [&](std::ostream& out) {
    out << "# once-scattered R_1(r), annulus averages per unit area per unit incident power\n"
           "r_lo,r_hi,monte_carlo,monte_carlo_stderr,exact,exact_error,z\n";
    for (std::size_t i = 0; i < nr; ++i) {
      const double z = mc.stderr_of_mean[i] > 0.0
                           ? (mc.mean[i] - exact.mean[i]) / mc.stderr_of_mean[i]
                           : std::numeric_limits<double>::quiet_NaN();
      out << fmt::format("{},{},{:.9g},{:.9g},{:.9g},{:.3g},{}\n", r_edges[i], r_edges[i + 1],
                         mc.mean[i], mc.stderr_of_mean[i], exact.mean[i], exact.error[i],
                         nan_or(z));
    }
  });
  std::vector<double> r(nr);
  for (std::size_t i = 0; i < nr; ++i) r[i] = 0.5 * (r_edges[i] + r_edges[i + 1]);
  LinePlot plot{
      "Searchlight, reflectance of light scattered once: Monte Carlo against the exact "
      "refractive single-scatter solution\n" +
          title_of(medium),
      "distance from the beam $r$ (mfp)",
      "$R_1(r)$ (mfp$^{-2}$ per unit incident power)",
      AxisScale::log,
      false,
      {}};
  plot.series.push_back(
      {"Monte Carlo ±1σ, once scattered", r, mc.mean, mc.stderr_of_mean, true, "monte_carlo"});
  plot.series.push_back({"exact single scattering", r, exact.mean, {}, false, "exact"});
  const auto png = directory / fmt::format("{}_single_scatter_log.png", stem);
  write_png(plot, png);
  return {csv, png};
}

std::vector<std::filesystem::path> write_lit_sphere_report(
    const std::vector<LitSphereComparison>& comparisons, const std::filesystem::path& directory) {
  if (comparisons.empty()) throw std::logic_error("no lit sphere comparison to write");
  make_output_directory(directory, "--out");
  std::vector<std::filesystem::path> written;
  const auto exitance_csv = directory / "litsphere_exitance.csv";
  write_text_file(exitance_csv, [&](std::ostream& out) {
    out << "case,length_unit,psi_lo_deg,psi_hi_deg,mc_all,mc_all_stderr,mc_multiple,"
           "mc_multiple_stderr";
    for (const LitSphereModelCurve& m : comparisons.front().models)
      out << ',' << to_string(m.model) << ',' << to_string(m.model) << "_stderr";
    out << '\n';
    for (const LitSphereComparison& c : comparisons) {
      for (std::size_t b = 0; b + 1 < c.psi_edges.size(); ++b) {
        out << fmt::format("{},{},{:.6g},{:.6g},{},{},{},{}", c.lit_case.slug,
                           c.lit_case.medium.length_unit, c.psi_edges[b] / degree_in_radians,
                           c.psi_edges[b + 1] / degree_in_radians, nan_or(c.all.mean[b]),
                           nan_or(c.all.stderr_of_mean[b]), nan_or(c.multiple.mean[b]),
                           nan_or(c.multiple.stderr_of_mean[b]));
        for (const LitSphereModelCurve& m : c.models)
          out << ',' << nan_or(m.exitance.mean[b]) << ',' << nan_or(m.exitance.stderr_of_mean[b]);
        out << '\n';
      }
    }
  });
  written.push_back(exitance_csv);

  const auto errors_csv = directory / "litsphere_errors.csv";
  write_text_file(errors_csv, [&](std::ostream& out) {
    out << "case,model,lit_error,terminator_error,shadow_error\n";
    for (const LitSphereComparison& c : comparisons)
      for (const LitSphereModelCurve& m : c.models)
        out << fmt::format("{},{},{},{},{}\n", c.lit_case.slug, to_string(m.model),
                           nan_or(m.lit_error), nan_or(m.terminator_error), nan_or(m.shadow_error));
  });
  written.push_back(errors_csv);

  std::vector<PlotFile> figures;
  for (const LitSphereComparison& c : comparisons) {
    std::vector<double> psi(c.psi_edges.size() - 1);
    for (std::size_t b = 0; b < psi.size(); ++b)
      psi[b] = 0.5 * (c.psi_edges[b] + c.psi_edges[b + 1]) / degree_in_radians;
    const std::string unit = c.lit_case.medium.length_unit;
    LinePlot plot;
    plot.title = fmt::format("Lit sphere under a directional light: {}\n{}, $\\eta$ = {:g}",
                             c.lit_case.name, medium_text(c.lit_case.medium), c.lit_case.eta);
    plot.x_label = "angle from the lit pole $\\psi$ (degrees; terminator at 90)";
    plot.y_label =
        fmt::format("exitance $M(\\psi)$ ({}$^{{-2}}$ per unit power meeting the sphere)", unit);
    plot.y_scale = AxisScale::log;
    plot.series.push_back({"Monte Carlo, scattered at least twice ±1σ", psi, c.multiple.mean,
                           c.multiple.stderr_of_mean, true, "monte_carlo"});
    plot.series.push_back({"Monte Carlo, every order ±1σ", psi, c.all.mean, c.all.stderr_of_mean,
                           true, "monte_carlo_all_orders"});
    for (const LitSphereModelCurve& m : c.models)
      plot.series.push_back({display_name(to_string(m.model)),
                             psi,
                             m.exitance.mean,
                             {},
                             false,
                             style_key(to_string(m.model))});
    figures.push_back({plot, directory / fmt::format("litsphere_{}.png", c.lit_case.slug)});
  }
  write_pngs(figures);
  for (const PlotFile& f : figures) written.push_back(f.path);
  return written;
}

std::string lit_sphere_error_table(const std::vector<LitSphereComparison>& comparisons) {
  std::string table = fmt::format("  {:<52} {:<22} {:>9} {:>11} {:>9}\n", "case", "model", "lit",
                                  "terminator", "shadow");
  const auto percent = [](double v) {
    return std::isnan(v) ? std::string("—") : fmt::format("{:.1f}%", 100.0 * v);
  };
  for (const LitSphereComparison& c : comparisons)
    for (const LitSphereModelCurve& m : c.models)
      table +=
          fmt::format("  {:<52} {:<22} {:>9} {:>11} {:>9}\n", c.lit_case.name, to_string(m.model),
                      percent(m.lit_error), percent(m.terminator_error), percent(m.shadow_error));
  return table;
}

}  // namespace scatterlab
