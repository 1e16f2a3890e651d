#include "scatterlab/refract/path_contribution.hpp"

#include <array>
#include <cmath>

#include "scatterlab/core/fresnel.hpp"

namespace scatterlab {

double refraction_distance_factor(const RefractiveTriangle& tri, const RefractionPath& path,
                                  double eta, bool directional_light) {
  const Vec3 d = -path.omega_v;
  const Vec3& n = path.shading_normal;
  const Vec3& ng = tri.geometric_normal;
  const Vec3& omega_l = path.omega_l;
  const double cos_i = d.dot(n);
  const double cos_o = omega_l.dot(n);
  const double mu = cos_o - eta * cos_i;
  const double length_n =
      (tri.n0 + path.bary_a * tri.dn1 + path.bary_b * tri.dn2).norm();
  const Frame frame(d);
  std::array<Vec3, 2> moved;
  for (std::size_t k = 0; k < 2; ++k) {
    const Vec3& e = k == 0 ? frame.tangent : frame.bitangent;
    const Vec3 dp = path.distance_v * (e - d * (e.dot(ng) / d.dot(ng)));
    Vec3 dn = Vec3::Zero();
    if (tri.smooth) {
      const Eigen::Vector2d dab = tri.barycentric(tri.p0 + dp);
      const Vec3 raw = dab.x() * tri.dn1 + dab.y() * tri.dn2;
      dn = (raw - n * n.dot(raw)) / length_n;
    }
    const double d_cos_i = e.dot(n) + d.dot(dn);
    const double d_mu = d_cos_i * (eta * eta * cos_i / cos_o - eta);
    const Vec3 d_omega_l = eta * e + d_mu * n + mu * dn;
    moved[k] = directional_light
                   ? d_omega_l
                   : Vec3(dp - dp.dot(omega_l) * omega_l + path.distance_l * d_omega_l);
  }
  return moved[0].cross(moved[1]).norm();
}

double flat_refraction_distance_factor(const RefractionPath& path, double eta,
                                       bool directional_light) {
  const double cos_v = std::abs(path.omega_v.dot(path.shading_normal));
  const double cos_l = std::abs(path.omega_l.dot(path.shading_normal));
  if (directional_light) return eta * eta * cos_v / cos_l;
  const double d_v = path.distance_v, d_l = path.distance_l;
  return (d_v + eta * d_l) * (d_v * cos_l / cos_v + eta * d_l * cos_v / cos_l);
}

PathContribution path_contribution(const RefractiveTriangle& tri, const RefractionPath& path,
                                   double eta, double sigma_t, bool directional_light,
                                   const ContributionOptions& options) {
  PathContribution c;
  c.transmittance = fresnel_dielectric_transmittance(path.omega_l.dot(path.shading_normal), eta);
  c.attenuation = std::exp(-sigma_t * path.distance_v);
  c.distance_factor = refraction_distance_factor(tri, path, eta, directional_light);
  if (c.distance_factor < options.min_distance_factor) {
    c.distance_factor = options.min_distance_factor;
    c.clamped = true;
  }
  c.irradiance = c.transmittance * eta * eta * c.attenuation / c.distance_factor;
  return c;
}

}  // namespace scatterlab
