#pragma once
// The layered slab of MCML (Wang, Jacques & Zheng 1995): a stack of plane-parallel layers, each
// with its own mu_a, mu_s, g, refractive index and thickness (the last may be semi-infinite),
// between ambient media above and below, lit by a pencil beam at normal incidence at the origin.
// What the run is asked to do, validated once, and the run on the engine (slab.hpp).
//
// Tallies, per unit incident power, as MCML scores them (the MCML manual, Wang & Jacques 1992,
// "Scored physical quantities"): the specular reflectance R_sp (exact), the diffuse reflectance
// R_d and total transmittance T_t (unscattered light included) in total, by r, by exit angle
// theta_o (MCML's alpha, per steradian) and by both (a radiance: per projected steradian, as
// MCML's R_d(r, alpha) is), the absorbed power in total, by layer, by depth A(z) and by (r, z);
// reflectance, transmittance and the absorbed total also by scattering order. Every bin is
// divided by its exact measure (io/mco_file.hpp rescales to MCML's midpoint measures). Analog,
// every photon ends in exactly one of them, so R_sp + R_d + T_t + A = 1 photon by photon.
//
// Lengths are in length_unit ("um", "mm", "cm", "m", or "mfp", where every turbid layer has
// mu_a + mu_s = 1), mu_a and mu_s in its inverse. Unlike the other scenes, the slab is
// transported in this unit, since each layer has its own mean free path.

#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "scatterlab/core/medium.hpp"
#include "scatterlab/tally/axis.hpp"
#include "scatterlab/transport/declared_tally.hpp"
#include "scatterlab/transport/engine.hpp"
#include "scatterlab/transport/run_settings.hpp"
#include "scatterlab/transport/weighting.hpp"

namespace scatterlab {

struct SlabLayerSpec {
  double mu_a = 1.0;       // absorption coefficient, >= 0, 1 / length_unit
  double mu_s = 100.0;     // scattering coefficient, >= 0; mu_a = mu_s = 0 is a clear layer
  double g = 0.9;          // Henyey-Greenstein mean cosine, |g| < 1
  double n = 1.4;          // refractive index
  double thickness = 0.1;  // > 0, length_unit; infinite for a semi-infinite last layer
  std::optional<MaterialOrigin> material;  // set when the layer came from a measured table

  double mu_t() const { return mu_a + mu_s; }
  bool clear() const { return mu_a == 0.0 && mu_s == 0.0; }
};

struct LayeredSlabSpec {
  std::vector<SlabLayerSpec> layers{SlabLayerSpec{}};  // top down
  std::string length_unit = "cm";
  double n_above = 1.0, n_below = 1.0;
  UniformAxis r{0.0, 0.5, 50};                           // distance from the beam, length_unit
  UniformAxis z{0.0, 0.4, 40};                           // depth, length_unit
  UniformAxis theta_o{0.0, std::numbers::pi / 2.0, 30};  // exit angle from the outward normal
  bool split_by_order = true;  // siblings _unscattered, _single, _multiple
  Weighting weighting = Weighting::analog;
  RunSettings run{1'000'000, 64, 1, 0};
  // [[tally]]: tallies the scene declares beside its own (declared_tally.hpp).
  std::vector<DeclaredTally> declared_tallies = {};

  // Throws InputError naming the first bad field ("layers[2].mu_s", "grid.r.bins", ...) and
  // what it accepts.
  void validate() const;
};

// The light reflected where the beam meets the slab, known before any photon runs: Fresnel at
// normal incidence between the medium above and the first layer; when the first layer is clear,
// its two surfaces' multiple reflections, r1 + (1 - r1)^2 r2 / (1 - r1 r2) (MCML's Rspecular; the
// manual, "Launching a photon packet").
double specular_reflectance(const LayeredSlabSpec& spec);

// What shapes the tallies: equal for a run and its resumption (run_settings.hpp).
std::string fingerprint(const LayeredSlabSpec& spec);

// The engine's problem: the slab, the beam (at the top of the second layer when the first is
// clear, as MCML launches it), the declared tallies.
TransportProblem transport_problem(const LayeredSlabSpec& spec);

// Runs the spec on the transport engine; only the root rank gets tallies.
TransportOutput run_layered_slab(const LayeredSlabSpec& spec, const ProgressCallback& progress = {},
                                 const RunControl& control = {});

std::string to_string(Weighting weighting);

}  // namespace scatterlab
