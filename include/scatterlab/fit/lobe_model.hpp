#pragma once
// The lobe models, written once for doubles and Ceres Jets, and their descriptions.
//
// Every model is evaluated as log L(omega) from an axis p (a unit 3-vector in the local frame
// (e_r, e_phi, e_z)) and a few shape parameters; the fits work in log L (see lobe_fit.hpp).
//
//   sg      spherical Gaussian, axis fixed to the vector irradiance E (Vavassori §4.2.1):
//           G(v) = mu exp(lambda (v.p - 1)); shape (lambda, log mu)
//   sg_free the same with p free on the sphere (a Ceres SphereManifold)
//   dexp    double exponential (Vavassori §4.2.2): L = alpha exp(beta e^{gamma sqrt(1 - p.w)});
//           shape (log alpha, beta, gamma), p free
//   adexp   anisotropic double exponential (this project, beyond §4.2): 1 - p.w = |w - p|^2 / 2
//           is split along the two tangents of p, one in the lobe's plane of symmetry (phi = 0)
//           and one across it, and the two are scaled by e^{eta} and e^{-eta}: a lobe flattened
//           across the plane (Figs. 4.6, 4.10) has eta < 0. eta = 0 is dexp. shape
//           (log alpha, beta, gamma, eta), p free.
//
// sqrt(1 - p.w) has an unbounded derivative at w = p when written that way. Written as a norm,
// |w - p| / sqrt 2 (p and w unit), its gradient has length at most 1/sqrt 2 everywhere; only the
// point w = p itself has no gradient, and there the subgradient 0 is returned so that residuals
// and Jacobians stay finite.

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <span>
#include <string>
#include <vector>

namespace scatterlab::fit {

enum class LobeModel { sg, sg_free, dexp, adexp };

inline constexpr std::array<LobeModel, 4> kAllLobeModels = {LobeModel::sg, LobeModel::sg_free,
                                                            LobeModel::dexp, LobeModel::adexp};

// "sg", "sg_free", "dexp", "adexp".
std::string to_string(LobeModel model);
// Throws InputError("models", ...) for an unknown name.
LobeModel parse_lobe_model(const std::string& name);
// Comma-separated list, e.g. "sg,dexp"; throws InputError("models", ...).
std::vector<LobeModel> parse_lobe_models(const std::string& list);
// One line: the formula and where it comes from.
std::string describe(LobeModel model);

// The parameters a Ceres problem moves: the axis and up to four shape parameters.
struct LobeParameters {
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  std::array<double, 4> shape{};
};

// What users see, in order: the model's parameters as the papers write them, then p.
std::vector<std::string> parameter_names(LobeModel model);
std::vector<double> reported_parameters(LobeModel model, const LobeParameters& parameters);

namespace detail {

// sqrt(x) for x >= 0 with the subgradient 0 at x = 0, so that a Jet never divides by zero.
template <typename T>
T sqrt_zero_safe(const T& x) {
  using std::sqrt;
  if (x > T(0)) return sqrt(x);
  return T(0) * x;
}

template <typename T>
T dot(const T* axis, const Eigen::Vector3d& w) {
  return axis[0] * w.x() + axis[1] * w.y() + axis[2] * w.z();
}

// sqrt(1 - p.w) = |w - p| / sqrt 2 for unit p and w (see the header comment).
template <typename T>
T half_chord(const T* axis, const Eigen::Vector3d& w) {
  const T dx = T(w.x()) - axis[0], dy = T(w.y()) - axis[1], dz = T(w.z()) - axis[2];
  return sqrt_zero_safe(T(0.5) * (dx * dx + dy * dy + dz * dz));
}

}  // namespace detail

// Vavassori §4.2.1, the SG: log G = log mu + lambda (v.p - 1). shape = (lambda, log mu).
struct SphericalGaussian {
  static constexpr int kShape = 2;
  template <typename T>
  static T log_value(const T* axis, const T* shape, const Eigen::Vector3d& w) {
    return shape[1] + shape[0] * (detail::dot(axis, w) - T(1));
  }
};

// Vavassori §4.2.2: log L = log alpha + beta exp(gamma sqrt(1 - p.w)).
// shape = (log alpha, beta, gamma).
struct DoubleExponential {
  static constexpr int kShape = 3;
  template <typename T>
  static T log_value(const T* axis, const T* shape, const Eigen::Vector3d& w) {
    using std::exp;
    return shape[0] + shape[1] * exp(shape[2] * detail::half_chord(axis, w));
  }
};

// The anisotropic double exponential: sqrt(1 - p.w) replaced by
//   s_eta = sqrt((e^{eta} (w.t1)^2 + e^{-eta} (w.t2)^2 + (1 - w.p)^2) / 2),
// with t2 the unit tangent of p across the plane of symmetry (along e_phi, or along e_r when p
// lies on the e_phi axis) and t1 = t2 x p in the plane. For eta = 0 the sum is |w - p|^2, so
// s_0 = sqrt(1 - p.w). shape = (log alpha, beta, gamma, eta).
struct AnisotropicDoubleExponential {
  static constexpr int kShape = 4;
  template <typename T>
  static T log_value(const T* axis, const T* shape, const Eigen::Vector3d& w) {
    using std::exp;
    using std::sqrt;
    // t2 = (e - (e.p) p) / |...| for e = e_phi, or e_r when p is (nearly) along e_phi.
    const bool along_phi = axis[1] * axis[1] > T(1.0 - 1e-9);
    const int k = along_phi ? 0 : 1;
    const T norm = sqrt(T(1) - axis[k] * axis[k]);
    T t2[3] = {-axis[k] * axis[0], -axis[k] * axis[1], -axis[k] * axis[2]};
    t2[k] += T(1);
    for (T& c : t2) c /= norm;
    const T t1[3] = {t2[1] * axis[2] - t2[2] * axis[1], t2[2] * axis[0] - t2[0] * axis[2],
                     t2[0] * axis[1] - t2[1] * axis[0]};
    const T along_plane = detail::dot(t1, w), across_plane = detail::dot(t2, w);
    const T radial = T(1) - detail::dot(axis, w);
    const T s = detail::sqrt_zero_safe(
        T(0.5) * (exp(shape[3]) * along_plane * along_plane +
                  exp(-shape[3]) * across_plane * across_plane + radial * radial));
    return shape[0] + shape[1] * exp(shape[2] * s);
  }
};

// log of the model at one direction, for doubles (tests, errors, estimates).
double log_model_value(LobeModel model, const LobeParameters& parameters,
                       const Eigen::Vector3d& direction);

}  // namespace scatterlab::fit
