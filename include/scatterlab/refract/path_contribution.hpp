#pragma once
// The light a refracted path carries to V (Walter et al. 2009, §4, eq. 17: I_e F A rho / D).
//
// D is rederived here from ray differentials (Igehy 1999), since eqs. 19-26 are garbled in our
// copy. Trace back from V: the ray leaves V along d = -omega_V, reaches P after t = d_V, refracts
// about N_s into omega_L = eta d + mu N_s with mu = cos_o - eta cos_i (cos_i = d . N_s,
// cos_o = omega_L . N_s = sqrt(1 - eta^2 (1 - cos_i^2))), and travels d_L to L. Perturb d by a
// unit vector e perpendicular to it (d' = e):
//   P'      = t (e - d (e . N_g) / (d . N_g))                     (P stays on the plane)
//   N_s'    = (n' - N_s (N_s . n')) / |n|, n' from the barycentric motion of P'
//   cos_i'  = e . N_s + d . N_s'
//   mu'     = cos_i' (eta^2 cos_i / cos_o - eta)
//   omega_L'= eta e + mu' N_s + mu N_s'
//   L'      = P' - (P' . omega_L) omega_L + d_L omega_L'           (in the plane normal to omega_L)
// and D = |L'_1 x L'_2| for two orthonormal e (eq. 26): the area at L per unit solid angle at V,
// dA_L / dOmega_V. For a directional light, D = |omega_L'_1 x omega_L'_2| = dOmega_L / dOmega_V.
//
// Radiometry (etendue n^2 dA dOmega is conserved): the irradiance at V, normal to the arriving
// ray, from a point light of intensity I is E = I T eta^2 A / D, and from a directional light of
// irradiance E_0 (normal to its beam) E = E_0 T eta^2 A / D. Walter's eq. 17 leaves out eta^2 (a
// basic-radiance convention); here it is explicit so that energy balances (tested).

#include <limits>

#include "scatterlab/refract/refraction_path.hpp"
#include "scatterlab/refract/triangle_search.hpp"

namespace scatterlab {

// D by ray differentials (valid for any shading normals), as above.
double refraction_distance_factor(const RefractiveTriangle& tri, const RefractionPath& path,
                                  double eta, bool directional_light);

// Walter eq. 18 (flat facet, N_s = N_g), with the eta on the second term that reduces it to
// (d_V + eta d_L)^2 at normal incidence, as the paper states:
//   D = (d_V + eta d_L) (d_V cos_L / cos_V + eta d_L cos_V / cos_L);
// for a directional light, the limit D / d_L^2 = eta^2 cos_V / cos_L.
double flat_refraction_distance_factor(const RefractionPath& path, double eta,
                                       bool directional_light);

struct ContributionOptions {
  // Caustic clamp: D is raised to at least this value (off when 0); every use is recorded.
  double min_distance_factor = 0.0;
};

struct PathContribution {
  double transmittance = 0.0;    // Fresnel T at P, entering the medium (core/fresnel.hpp)
  double attenuation = 0.0;      // exp(-sigma_t d_V): the path inside the medium
  double distance_factor = 0.0;  // D as used (after the clamp, if it acted)
  bool clamped = false;
  // E at V normal to the arriving ray per unit light intensity (point light, 1/length^2) or per
  // unit light irradiance (directional, dimensionless): T eta^2 A / D.
  double irradiance = 0.0;
};

PathContribution path_contribution(const RefractiveTriangle& tri, const RefractionPath& path,
                                   double eta, double sigma_t, bool directional_light,
                                   const ContributionOptions& options = {});

}  // namespace scatterlab
