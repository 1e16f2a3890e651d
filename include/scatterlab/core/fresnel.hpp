#pragma once
// Fresnel reflectance and transmittance of a smooth dielectric interface for unpolarised light
// (Born & Wolf, "Principles of Optics", §1.5.2, eqs. 20-21; pbrt-v4 FrDielectric).

#include <algorithm>
#include <cmath>

namespace scatterlab {

// cos_incident: cosine of the angle between the incident ray and the normal, on the incident
// side, in [0, 1]. eta: n_transmitted / n_incident (> 0). Returns 1 under total internal
// reflection (sin_t >= 1) and exactly 0 at eta = 1.
inline double fresnel_dielectric_reflectance(double cos_incident, double eta) {
  const double cos_i = std::clamp(cos_incident, 0.0, 1.0);
  if (eta == 1.0) return 0.0;
  // Snell: sin_t = sin_i / eta.
  const double sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1.0) return 1.0;
  const double cos_t = std::sqrt(1.0 - sin2_t);
  const double r_s = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  const double r_p = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  return 0.5 * (r_s * r_s + r_p * r_p);
}

inline double fresnel_dielectric_transmittance(double cos_incident, double eta) {
  return 1.0 - fresnel_dielectric_reflectance(cos_incident, eta);
}

}  // namespace scatterlab
