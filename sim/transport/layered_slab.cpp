#include "scatterlab/transport/layered_slab.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "scatterlab/core/error.hpp"
#include "scatterlab/core/fresnel.hpp"
#include "scatterlab/tally/filter.hpp"
#include "scatterlab/transport/grid_checks.hpp"
#include "scatterlab/transport/searchlight.hpp"

namespace scatterlab {

namespace {

constexpr std::size_t max_layers = 1000;

std::string got(double value) {
  return fmt::format("got {}", value);
}

std::string layer_field(std::size_t i, const char* key) {
  return fmt::format("layers[{}].{}", i + 1, key);
}

void check_index(double n, const std::string& field) {
  if (!(n >= min_eta && n <= max_eta)) {
    throw InputError(field, got(n), "a refractive index in [0.1, 10]");
  }
}

void check_layer(const SlabLayerSpec& layer, std::size_t i, std::size_t count,
                 const std::string& unit) {
  for (const auto& [value, key] : {std::pair{layer.mu_a, "mu_a"}, std::pair{layer.mu_s, "mu_s"}}) {
    if (!(value >= 0.0) || !std::isfinite(value)) {
      throw InputError(layer_field(i, key), got(value),
                       fmt::format("a finite number >= 0 (per {})", unit));
    }
  }
  if (!(std::abs(layer.g) < 1.0)) {
    throw InputError(layer_field(i, "g"), got(layer.g),
                     "a number in (-1, 1) (the Henyey-Greenstein mean cosine)");
  }
  check_index(layer.n, layer_field(i, "n"));
  const bool last = i + 1 == count;
  if (!(layer.thickness > 0.0) || std::isnan(layer.thickness) ||
      (std::isinf(layer.thickness) && !last)) {
    throw InputError(layer_field(i, "thickness"), got(layer.thickness),
                     fmt::format("a finite number > 0 (in {}); only the last layer may be "
                                 "infinite (semi-infinite)",
                                 unit));
  }
  if (std::isinf(layer.thickness) && layer.clear()) {
    throw InputError(layer_field(i, "thickness"), "is infinite in a clear layer",
                     "a finite thickness, or a turbid layer (mu_a + mu_s > 0): a clear "
                     "semi-infinite layer is the medium below (n_below)");
  }
  if (unit == "mfp" && !layer.clear() && layer.mu_t() != 1.0) {
    throw InputError(layer_field(i, "mu_a, mu_s"),
                     fmt::format("sum to {} with length_unit = \"mfp\"", layer.mu_t()),
                     "mu_a + mu_s = 1 (or 0, clear) in mean free paths; a physical "
                     "length_unit for layers of different extinction");
  }
  // Past these a flight's length, tau / sigma_t, leaves the doubles' comfortable range.
  if (!layer.clear() && !(layer.mu_t() >= 1e-9 && layer.mu_t() <= 1e12)) {
    throw InputError(layer_field(i, "mu_a, mu_s"), fmt::format("sum to {}", layer.mu_t()),
                     fmt::format("mu_a + mu_s in [1e-9, 1e12] per {}, or 0 (clear)", unit));
  }
}

// MCML's tallies (the manual, "Scored physical quantities"), each declared once.
std::vector<TallyDeclaration> declare_tallies(const LayeredSlabSpec& spec) {
  const Filter r = radius_filter(spec.r);
  const Filter angle = exit_solid_angle_filter(spec.theta_o);
  std::vector<TallyDeclaration> tallies;
  struct Side {
    const char* name;
    Score score;
    const char* what;
  };
  for (const Side& side :
       {Side{"diffuse_reflectance", Score::exitance, "leaving through the lit side z = 0 (R_d)"},
        Side{"total_transmittance", Score::transmittance,
             "leaving through the far side, unscattered light included (T_t)"}}) {
    const std::string name = side.name;
    tallies.push_back({name, side.score, {}, Units{}, fmt::format("power {}", side.what), true});
    tallies.push_back({name + "_by_radius",
                       side.score,
                       {r},
                       Units{1, -2},
                       fmt::format("power {} per unit area of the ring at distance r from the "
                                   "beam, ring average",
                                   side.what),
                       true});
    tallies.push_back({name + "_by_angle",
                       side.score,
                       {angle},
                       Units{1, 0, -1},
                       fmt::format("power {} per steradian at exit angle theta_o from the "
                                   "outward normal (outside), bin average",
                                   side.what),
                       true});
    tallies.push_back({name + "_by_radius_angle",
                       side.score,
                       {r, exit_angle_filter(spec.theta_o)},
                       Units{1, -2, -1},
                       fmt::format("radiance {}: power per unit area and projected solid angle "
                                   "(cos theta_o d omega), by r and theta_o, bin average",
                                   side.what),
                       true});
  }
  tallies.push_back({"absorbed", Score::absorbed, {}, Units{}, "power absorbed in the slab", true});
  tallies.push_back({"absorbed_by_layer",
                     Score::absorbed,
                     {layer_filter(spec.layers.size())},
                     Units{},
                     "power absorbed in each layer, top down"});
  tallies.push_back({"absorbed_by_depth",
                     Score::absorbed,
                     {depth_filter(spec.z)},
                     Units{1, -1},
                     "power absorbed per unit depth A(z), over all r, bin average"});
  tallies.push_back({"absorbed_by_radius_depth",
                     Score::absorbed,
                     {r, depth_filter(spec.z)},
                     Units{1, -3},
                     "power absorbed per unit volume A(r, z), bin average"});
  tallies.push_back({"specular_reflectance",
                     Score::exact,
                     {},
                     Units{},
                     "light reflected where the beam meets the slab (R_sp; exact: no standard "
                     "error)",
                     false,
                     specular_reflectance(spec)});
  return tallies;
}

}  // namespace

std::string to_string(Weighting weighting) {
  return weighting == Weighting::analog ? "analog" : "implicit";
}

void LayeredSlabSpec::validate() const {
  if (length_unit != "mfp" && !is_physical_length_unit(length_unit)) {
    throw InputError("geometry.length_unit", fmt::format("got \"{}\"", length_unit),
                     "\"um\", \"mm\", \"cm\", \"m\" or \"mfp\"");
  }
  if (layers.empty() || layers.size() > max_layers) {
    throw InputError("layers", fmt::format("has {} layers", layers.size()),
                     "1 to 1000 layers, top down");
  }
  for (std::size_t i = 0; i < layers.size(); ++i) {
    check_layer(layers[i], i, layers.size(), length_unit);
  }
  if (layers.size() == 1 && layers[0].clear()) {
    throw InputError("layers[1].mu_a, mu_s", "are 0 in the only layer",
                     "at least one turbid layer (mu_a + mu_s > 0)");
  }
  check_index(n_above, "geometry.n_above");
  check_index(n_below, "geometry.n_below");
  check_from_zero(r, "r", "the distance from the beam", "geometry.length_unit");
  check_from_zero(z, "z", "the lit surface", "geometry.length_unit");
  if (theta_o.min != 0.0 || std::abs(theta_o.max - 0.5 * std::numbers::pi) > 1e-12) {
    throw InputError("grid.theta_o", fmt::format("spans [{}, {}]", theta_o.min, theta_o.max),
                     "[0, pi/2]: exit angles from the outward normal");
  }
  check_bins(theta_o, "theta_o");
  check_run_settings(run);
  // A walk ends by absorption, or by leaving the slab. With albedo 1 in a semi-infinite layer the
  // number of events before a photon leaves has infinite mean (a recurrent 1-D walk in depth),
  // so a run would have no bounded cost: an escape radius bounds it.
  double albedo = 0.0, most_mu_t = 0.0;
  for (const SlabLayerSpec& l : layers) {
    if (!l.clear()) albedo = std::max(albedo, l.mu_s / l.mu_t());
    most_mu_t = std::max(most_mu_t, l.mu_t());
  }
  if (std::isinf(layers.back().thickness) && layers.back().mu_a == 0.0 &&
      !std::isfinite(run.escape_radius)) {
    throw InputError("run.escape_radius", "is infinite with mu_a = 0 in the semi-infinite layer",
                     fmt::format("a finite radius (in {}) past which photons are stopped, or "
                                 "mu_a > 0 in the last layer",
                                 length_unit));
  }
  double optical_depth = 0.0;
  for (const SlabLayerSpec& l : layers) optical_depth += l.mu_t() * l.thickness;
  // Photons leave a finite slab after about its optical depth squared events (diffusion); in a
  // semi-infinite one the last layer's absorption ends them.
  const SlabLayerSpec& last = layers.back();
  if (std::isinf(last.thickness)) albedo = last.mu_s / last.mu_t();
  check_run_length(run, albedo, std::min(run.escape_radius * most_mu_t, optical_depth));
  check_declared_tallies(declared_tallies,
                         slab_frame(length_unit, static_cast<int>(layers.size())));
}

double specular_reflectance(const LayeredSlabSpec& spec) {
  const double n1 = spec.layers[0].n;
  const double r1 = fresnel_dielectric_reflectance(1.0, n1 / spec.n_above);
  if (!spec.layers[0].clear() || spec.layers.size() < 2) return r1;
  const double r2 = fresnel_dielectric_reflectance(1.0, spec.layers[1].n / n1);
  return r1 + (1.0 - r1) * (1.0 - r1) * r2 / (1.0 - r1 * r2);
}

std::string fingerprint(const LayeredSlabSpec& spec) {
  std::string text = fmt::format("layered_slab|unit {}|n {:a} {:a}|", spec.length_unit,
                                 spec.n_above, spec.n_below);
  for (const SlabLayerSpec& l : spec.layers) {
    text += fmt::format("layer {:a} {:a} {:a} {:a} {:a}|", l.mu_a, l.mu_s, l.g, l.n, l.thickness);
  }
  text += fmt::format(
      "r {:a},{:a},{}|z {:a},{:a},{}|theta_o {}|split {}|weighting {}|run {} {} {} {:a}",
      spec.r.min, spec.r.max, spec.r.bins, spec.z.min, spec.z.max, spec.z.bins, spec.theta_o.bins,
      spec.split_by_order, to_string(spec.weighting), spec.run.photons, spec.run.batches,
      spec.run.seed, spec.run.escape_radius);
  return fingerprint_of(text + fingerprint_text(spec.declared_tallies));
}

TransportProblem transport_problem(const LayeredSlabSpec& spec) {
  TransportProblem problem;
  problem.geometry = GeometryKind::slab;
  for (const SlabLayerSpec& l : spec.layers) {
    problem.layers.push_back(
        {l.thickness, l.mu_t(), l.clear() ? 0.0 : l.mu_s / l.mu_t(), l.g, l.n});
  }
  problem.n_above = spec.n_above;
  problem.n_below = spec.n_below;
  problem.weighting = spec.weighting;
  // The beam enters at normal incidence, unbent; R_sp of it is reflected and 1 - R_sp carries
  // every other tally. Behind a clear first layer MCML starts it at the second layer's top, with
  // the clear layer's reflections in R_sp.
  problem.source.kind = Source::Kind::beam;
  problem.source.direction = Vec3::UnitZ();
  const bool clear_first = spec.layers[0].clear() && spec.layers.size() > 1;
  problem.source.position = Vec3(0.0, 0.0, clear_first ? spec.layers[0].thickness : 0.0);
  problem.photon_power = 1.0 - specular_reflectance(spec);
  problem.axes.r = spec.r;
  problem.axes.z = spec.z;
  problem.axes.theta_o = spec.theta_o;
  problem.tallies = declare_tallies(spec);
  for (TallyDeclaration& d : declare_chained_tallies(
           spec.declared_tallies,
           slab_frame(spec.length_unit, static_cast<int>(spec.layers.size())), problem.tallies)) {
    problem.tallies.push_back(std::move(d));
  }
  problem.length = {spec.length_unit, 1.0};  // transported in it
  problem.split_by_order = spec.split_by_order;
  problem.estimator = Estimator::collision;  // unused: a slab has no volume tallies
  problem.run = spec.run;
  problem.size_fields = "grid.r.bins x grid.z.bins, grid.r.bins x grid.theta_o.bins, run.threads";
  return problem;
}

TransportOutput run_layered_slab(const LayeredSlabSpec& spec, const ProgressCallback& progress,
                                 const RunControl& control) {
  spec.validate();
  return transport(transport_problem(spec), progress, control);
}

}  // namespace scatterlab
