#pragma once
// The lit sphere, like with like (Bitterli §3.5, §3.1.2): each diffusion BSSRDF integrated over a
// sphere under a directional light (models/lit_sphere_exitance.hpp) against the path-traced
// sphere of the same medium, radius, index and light (transport/lit_object.hpp), exitance
// M(psi) against the angle psi from the lit pole. The diffusion models describe the light
// scattered at least twice (validate/half_space_comparison.hpp), so each is held against the
// Monte Carlo's _multiple part; the total (every order) is kept beside it, to show what the
// once-scattered and unscattered light add. Beside the models, the same BSSRDF is built on the
// half-space's own multiply-scattered R_d(r), run by Monte Carlo in the same medium at normal
// incidence (models/diffusion_profile.hpp, a measured profile): what remains of its error is the
// BSSRDF construction's (a planar profile on a sphere, the chord for the distance, the direction
// of entry ignored), not diffusion theory's.
//
// Errors are mean |model - MC| / MC over the psi bins where the Monte Carlo part is resolved
// (mean > 3 standard errors), in three regions: the lit side (psi < 80 degrees), the
// terminator (80-100 degrees) and the shadow side (psi > 100 degrees); NaN where no bin of the
// region is resolved.

#include <cstdint>
#include <string>
#include <vector>

#include "scatterlab/models/diffusion_profile.hpp"
#include "scatterlab/models/lit_sphere_exitance.hpp"
#include "scatterlab/transport/lit_object.hpp"
#include "scatterlab/validate/half_space_comparison.hpp"

namespace scatterlab {

struct LitSphereCase {
  std::string name;     // "marble red (jensen2001, R = 10 mm)", "albedo 0.99, g 0, R = 10 mfp"
  std::string slug;     // file-name stem: "marble_red"
  Medium medium;        // coefficients in medium.length_unit
  double radius = 1.0;  // in medium.length_unit
  double eta = 1.3;
};

// The cases of `scatterlab validate litsphere`: Jensen et al. 2001's marble and skin1, each
// channel (R = 10 mm), and three media in mean free paths (albedo, g, R).
std::vector<LitSphereCase> lit_sphere_cases();

struct LitSphereSettings {
  std::uint64_t photons = 1'000'000;  // path-traced per case
  int threads = 0;
  std::uint64_t seed = 1;
  int integration_samples = 4'000;  // per psi bin and model
  int psi_bins = 36;
  int profile_rings = 400;  // of the half-space profile, out to the sphere's diameter
};

struct LitSphereModelCurve {
  ProfileModel model;  // measured: the half-space Monte Carlo's profile
  LitSphereExitance exitance;
  double lit_error = 0.0, terminator_error = 0.0, shadow_error = 0.0;
};

struct LitSphereComparison {
  LitSphereCase lit_case;
  std::vector<double> psi_edges;  // radians
  MonteCarloCurve all, multiple;  // exitance, 1 / length^2 per unit power meeting the sphere
  std::vector<LitSphereModelCurve> models;
  double transport_seconds = 0.0, integration_seconds = 0.0;
};

LitSphereComparison compare_lit_sphere(const LitSphereCase& lit_case,
                                       const LitSphereSettings& settings,
                                       const ProgressCallback& progress = {});

}  // namespace scatterlab
