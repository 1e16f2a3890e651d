#pragma once
// Reflection and refraction of unpolarised light at a smooth dielectric interface (Born & Wolf,
// "Principles of Optics", §1.5.2, eqs. (21a), (21b) with Snell's law; pbrt-v4 FrDielectric).
//
// `eta` is the relative index n_transmitted / n_incident: light going from air into a medium of
// index 1.33 sees 1.33, light leaving it sees 1 / 1.33. `cos_incident` is the cosine between the
// incident travel direction reversed and the normal on the incident side, in [0, 1].

#include <algorithm>
#include <cmath>

#include "scatterlab/core/frame.hpp"

namespace scatterlab {

struct FresnelDielectric {
  double reflectance_s = 0.0;    // |r_s|^2: electric field perpendicular to the plane of incidence
  double reflectance_p = 0.0;    // |r_p|^2: electric field in the plane of incidence
  double cos_transmitted = 1.0;  // cosine of the refracted direction; 0 under total reflection
  bool total_internal_reflection = false;

  double reflectance() const { return 0.5 * (reflectance_s + reflectance_p); }
};

// Snell's law: sin t = sin i / eta, so cos^2 t = 1 - (1 - cos^2 i) / eta^2; total internal
// reflection where this is negative (eta < 1 beyond the critical angle asin(eta)).
inline FresnelDielectric fresnel_dielectric_terms(double cos_incident, double eta) {
  const double cos_i = std::clamp(cos_incident, 0.0, 1.0);
  FresnelDielectric result;
  if (eta == 1.0) {  // no interface: nothing reflected, nothing bent
    result.cos_transmitted = cos_i;
    return result;
  }
  const double sin2_t = (1.0 - cos_i) * (1.0 + cos_i) / (eta * eta);
  if (sin2_t >= 1.0) {
    result.reflectance_s = result.reflectance_p = 1.0;
    result.cos_transmitted = 0.0;
    result.total_internal_reflection = true;
    return result;
  }
  const double cos_t = std::sqrt((1.0 - sin2_t));
  // Fresnel amplitudes (Born & Wolf eq. (21)): r_s = (cos i - eta cos t) / (cos i + eta cos t),
  // r_p = (eta cos i - cos t) / (eta cos i + cos t). Both denominators vanish only for
  // cos i = cos t = 0, i.e. eta = 1, handled above.
  const double r_s = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  const double r_p = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  result.reflectance_s = r_s * r_s;
  result.reflectance_p = r_p * r_p;
  result.cos_transmitted = cos_t;
  return result;
}

// Unpolarised reflectance F = (|r_s|^2 + |r_p|^2) / 2; exactly 0 for eta = 1, 1 under total
// internal reflection and at grazing incidence.
inline double fresnel_dielectric_reflectance(double cos_incident, double eta) {
  return fresnel_dielectric_terms(cos_incident, eta).reflectance();
}

inline double fresnel_dielectric_transmittance(double cos_incident, double eta) {
  return 1.0 - fresnel_dielectric_reflectance(cos_incident, eta);
}

// Snell's law in vector form (pbrt-v4 Refract): the unit travel direction `incident` refracted
// through a surface with unit normal `normal` pointing to the incident side, given
// cos_i = -incident . normal and the cos t of fresnel_dielectric_terms(cos_i, eta),
//   t = incident / eta + (cos i / eta - cos t) normal,
// for a caller that has the terms already (its Fresnel choice).
inline Vec3 refracted(const Vec3& incident, const Vec3& normal, double eta, double cos_i,
                      double cos_transmitted) {
  return (incident / eta + (cos_i / eta - cos_transmitted) * normal).normalized();
}

// Refracts `incident` through the surface with `normal` on the incident side
// (incident . normal < 0). Returns false under total internal reflection, leaving `transmitted`
// unchanged.
inline bool refract(const Vec3& incident, const Vec3& normal, double eta, Vec3& transmitted) {
  const double cos_i = -incident.dot(normal);
  const FresnelDielectric terms = fresnel_dielectric_terms(cos_i, eta);
  if (terms.total_internal_reflection) return false;
  transmitted = refracted(incident, normal, eta, cos_i, terms.cos_transmitted);
  return true;
}

}  // namespace scatterlab
