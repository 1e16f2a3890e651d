#pragma once
// The sections of `scatterlab report`: each runs its cases, compares them with an exact
// reference and returns a Section. The quick profile is sized for the test suite (a few
// minutes on 2 cores in all); the full profile for a workstation.

#include <cstdint>

#include "scatterlab/report/section.hpp"

namespace scatterlab::report {

struct Profile {
  bool quick = true;
  int threads = 0;  // 0: all hardware threads
  std::uint64_t seed = 1;
};

// Infinite medium, isotropic point source: Monte Carlo fluence on shells against the exact
// transport solution, at doubling photon budgets, for both estimators. Error against run time.
Section infinite_medium_convergence(const Profile& profile);

// Infinite medium, pencil beam, over albedo x g extremes: energy balance, the mean absorption
// depth 1 / (1 - albedo g) and the mean number of scattering events albedo / (1 - albedo).
Section infinite_medium_extremes(const Profile& profile);

// Half-space Monte Carlo: total diffuse reflectance against Chandrasekhar's H-function at
// doubling budgets (error against run time), and a matrix of extreme albedo, g, eta and
// incidence checked for energy, Fresnel specular reflection and the exact once-scattered light.
Section half_space_convergence(const Profile& profile);
Section half_space_extremes(const Profile& profile);

// The lit sphere: the unscattered exitance under the directional light against its exact
// quadrature at doubling budgets (error against run time), and a matrix of extreme albedo, g,
// eta and radius under the directional light and the pole beam checked for energy (by order too)
// and the exact unscattered light (reflected at entry, leaving, absorbed at the first collision).
Section sphere_convergence(const Profile& profile);
Section sphere_extremes(const Profile& profile);

// The layered slab: van de Hulst's R_d and T_t at doubling budgets (error against run time), and
// a matrix of extreme albedo, g, n and thickness checked for energy, the specular reflection and
// the exact unscattered light, with Giovanelli's semi-infinite medium.
Section slab_convergence(const Profile& profile);
Section slab_extremes(const Profile& profile);

// The half-space models (dipole, better dipole, quantized diffusion, Grosjean beam, exact single
// scatter) against the searchlight Monte Carlo part each models, over albedo x g x eta: totals
// and near / far errors, with the bound R_dr <= 1 checked.
Section half_space_model_accuracy(const Profile& profile);

// The models that approximate a continuum against it (quantized diffusion's Gaussians against
// its depth integral), on every ring out to the last its accuracy is stated for, at several
// tolerances: the worst error against the tolerance asked.
Section model_continua(const Profile& profile);

// Lobe fits against synthetic lobes of known parameters: parameter error against the
// quadrature order of the bin averages, and time per fit.
Section lobe_fit_accuracy(const Profile& profile);

// The refractive single-scatter solver on a bumpy sphere: heuristic and guaranteed search at
// several Newton tolerances, completeness against the guaranteed mode, Snell residuals, time.
Section refractive_solver_accuracy(const Profile& profile);

}  // namespace scatterlab::report
