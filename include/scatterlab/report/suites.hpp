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

// Objects bounded by a triangle mesh: a sphere mesh's unscattered exitance under the directional
// light against the exact value of its own polyhedron (quadrature over its lit facets) at doubling
// budgets; sphere meshes of 4 to 64 rings against their polyhedra and the analytic sphere (the
// tessellation's bias and its order); and a matrix of extreme albedo, g and eta, and a beam at
// grazing incidence, checked for energy, Fresnel reflection at entry and the unscattered light.
// Built with the renderer (SCATTERLAB_WITH_RENDER), as the next two.
Section mesh_convergence(const Profile& profile);
Section mesh_tessellation(const Profile& profile);
Section mesh_extremes(const Profile& profile);

// The volumetric path tracer: an absorbing sphere mesh's image against Beer-Lambert on its own
// chords at doubling budgets, and the white furnace (energy conservation, no path lost) with
// geometric and interpolated normals over eta and g.
Section volumetric_renderer_convergence(const Profile& profile);
Section volumetric_renderer_extremes(const Profile& profile);

// The lit sphere's BSSRDF integral (models/lit_sphere_exitance.hpp) against a deterministic
// quadrature of the same integral: at doubling samples (error against run time), and for each
// profile model over extreme albedo, eta and radius.
Section lit_sphere_bssrdf_convergence(const Profile& profile);
Section lit_sphere_bssrdf_extremes(const Profile& profile);

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
