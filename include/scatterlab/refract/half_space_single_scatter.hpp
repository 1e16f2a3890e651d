#pragma once
// The exact once-scattered reflectance of the searchlight half-space, the reference the Monte
// Carlo once-scattered tally is compared with.
//
// Geometry and normalisation: the medium fills z > 0 with relative index eta = eta_in / eta_out;
// a pencil beam of unit power enters at the origin along +z (normal incidence), losing the
// Fresnel reflectance R(0) at entry, so T_in = 1 - R(0) of it travels down the axis. At depth z
// a fraction sigma_s exp(-sigma_t z) dz scatters once, with the HG phase function p(cos theta)
// (cos theta = -cos theta_i for light turned back towards the surface at angle theta_i from the
// outward normal), travels straight to the surface point at radius r = z tan theta_i, and leaves
// with the exit Fresnel transmittance T(theta_i) (eta_out / eta_in, zero beyond the critical
// angle). Straight inside, refracted by Snell's law at the flat boundary: the refracted path the
// solver of Walter et al. 2009 finds for a plane (checked against it in the tests).
//
// R1(r) is the radiant exitance leaving the surface into the outside medium (after exit
// Fresnel transmission), per unit surface area at radius r, per unit incident power:
//   R1(r) = int_0^inf dz sigma_s T_in exp(-sigma_t z) p(-cos theta_i) T(theta_i)
//                        exp(-sigma_t z / cos theta_i) cos^3(theta_i) / z^2,
// in 1 / length_unit^2 of the Medium. Bin averages are (1 / (pi (r1^2 - r0^2))) times the
// power leaving through the annulus [r0, r1). At fixed z, r = z tan theta_i turns
// 2 pi r dr cos^3 / z^2 into 2 pi sin theta_i d theta_i; exchanging the order, at fixed theta_i
// the annulus is the depth range [r0, r1) / tan theta_i, over which the two exponentials
// integrate in closed form, leaving one adaptive Gauss-Kronrod integral over theta_i per annulus
// (the pointwise R1(r) below is integrated over z instead: the tests hold the two together).

#include <span>
#include <vector>

#include "scatterlab/core/medium.hpp"
#include "scatterlab/core/quadrature.hpp"

namespace scatterlab {

struct SingleScatterReflectance {
  std::vector<double> mean;   // bin averages of R1, per unit area per unit incident power
  std::vector<double> error;  // quadrature error estimate of each mean (absolute)
  double total = 0.0;         // int R1 2 pi r dr over all r: once-scattered reflectance
  double total_error = 0.0;
};

// r_edges: at least two, finite, non-negative and increasing (InputError "r_edges" otherwise).
SingleScatterReflectance half_space_single_scatter_reflectance(
    const Medium& medium, double eta, std::span<const double> r_edges,
    double rel_tol = 1e-9);

// R1 at one radius r > 0 (same units), with its quadrature error.
QuadratureResult half_space_single_scatter_exitance(const Medium& medium, double eta, double r,
                                                    double rel_tol = 1e-10);

}  // namespace scatterlab
