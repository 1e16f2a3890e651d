// scatterlab invert: the artist's parameters of a half-space, total diffuse reflectance R_dr and
// diffuse mean free path l_d, to the coefficients (sigma_a, sigma_s) a simulation takes, through
// any half-space model (Bitterli §3.4; models/parameter_inversion.hpp). One value, or one per
// channel (red, green, blue); the forward model evaluated at the answer is printed beside it, so
// the round trip is visible.
#include <fmt/format.h>

#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/core/medium.hpp"
#include "scatterlab/models/parameter_inversion.hpp"

namespace scatterlab::cli {
namespace {

struct InvertOptions {
  std::vector<double> total_reflectance, diffuse_mean_free_path;
  double eta = 1.3, g = 0.0;
  std::string model = "dipole";
  std::string length_unit = "mm";
};

int run_invert(const InvertOptions& o) {
  const HalfSpaceModel model = half_space_model_from_string(o.model, "--model");
  if (o.length_unit != "mfp" && !is_physical_length_unit(o.length_unit)) {
    throw InputError("--length-unit", fmt::format("got \"{}\"", o.length_unit),
                     "mfp, um, mm, cm or m");
  }
  if (o.total_reflectance.size() != 1 && o.total_reflectance.size() != 3) {
    throw InputError("--Rd", fmt::format("{} values", o.total_reflectance.size()),
                     "one value, or three: red, green and blue");
  }
  if (o.total_reflectance.size() != o.diffuse_mean_free_path.size()) {
    throw InputError("--ld",
                     fmt::format("{} values for {} values of --Rd", o.diffuse_mean_free_path.size(),
                                 o.total_reflectance.size()),
                     "as many values as --Rd (one per channel)");
  }
  static constexpr const char* kChannels[] = {"red", "green", "blue"};
  auto channel = [&o](std::size_t i) {
    return o.total_reflectance.size() == 1 ? "all" : kChannels[i];
  };
  std::vector<InvertedCoefficients> results;
  for (std::size_t i = 0; i < o.total_reflectance.size(); ++i) {
    results.push_back(
        invert_reflectance(model, o.total_reflectance[i], o.diffuse_mean_free_path[i], o.eta, o.g));
  }
  const std::string& unit = o.length_unit;
  fmt::print("scatterlab invert: model {}, eta {}, g {}; lengths in {}\n", to_string(model), o.eta,
             o.g, unit);
  fmt::print("  {:>8} {:>10} {:>10} {:>14} {:>14} {:>14} {:>10} {:>10}\n", "channel", "R_dr", "l_d",
             "alpha'", fmt::format("sigma_a /{}", unit), fmt::format("sigma_s /{}", unit),
             "R_dr back", "l_d back");
  for (std::size_t i = 0; i < results.size(); ++i) {
    const InvertedCoefficients& c = results[i];
    // The forward model at the answer: R_dr(alpha') and l_d = 1 / sigma_tr.
    const double sigma_t_reduced = c.sigma_a + c.sigma_s * (1.0 - o.g);
    const double back_r = total_diffuse_reflectance(model, c.reduced_albedo, o.eta);
    const double back_l =
        1.0 / (sigma_t_reduced * transport_to_extinction_ratio(model, c.reduced_albedo));
    fmt::print("  {:>8} {:>10.6g} {:>10.6g} {:>14.10f} {:>14.8g} {:>14.8g} {:>10.6g} {:>10.6g}\n",
               channel(i), o.total_reflectance[i], o.diffuse_mean_free_path[i], c.reduced_albedo,
               c.sigma_a, c.sigma_s, back_r, back_l);
  }
  return 0;
}

}  // namespace

Action add_invert_command(CLI::App& app) {
  auto o = std::make_shared<InvertOptions>();
  auto* command = app.add_subcommand(
      "invert",
      "Half-space parameters from appearance (Bitterli §3.4): total diffuse reflectance R_dr and "
      "diffuse mean free path l_d = 1 / sigma_tr to sigma_a and sigma_s, by bisection on the "
      "model's R_dr(alpha'). Give one value, or three: red, green and blue (--Rd 0.8 0.6 0.3 "
      "--ld 8 4 2).");
  command
      ->add_option("--Rd", o->total_reflectance,
                   "Total diffuse reflectance R_dr, in (0, what the model reaches at alpha' = 1)")
      ->required();
  command
      ->add_option("--ld", o->diffuse_mean_free_path,
                   "Diffuse mean free path l_d = 1 / sigma_tr, > 0, in --length-unit")
      ->required();
  command->add_option("--eta", o->eta, "Relative index n_medium / n_outside, in [0.5, 2.5]");
  command->add_option("--g", o->g, "Henyey-Greenstein g; sigma_s = sigma_s' / (1 - g)");
  std::string names;
  for (const HalfSpaceModel model : all_half_space_models) {
    names += (names.empty() ? "" : ", ") + to_string(model);
  }
  command->add_option("--model", o->model, "Half-space model: " + names);
  command->add_option("--length-unit", o->length_unit,
                      "Unit of l_d, and so of the coefficients: mfp, um, mm, cm or m");
  return [o] { return run_invert(*o); };
}

}  // namespace scatterlab::cli
