#pragma once
// The lobe models, written once for doubles and Ceres Jets, and their descriptions.
//
// Every model is evaluated as log L(omega) from an axis p (a unit 3-vector in the local frame
// (e_r, e_phi, e_z)) and a few shape parameters. The fit compares L itself with the tally
// (lobe_fit.hpp); log L is the form in which the models stay finite over the 60 decades a
// peaked lobe spans, and in which the bin averages are taken (lobe_fit.cpp, log_average).
//
//   sg         spherical Gaussian, axis fixed to the vector irradiance E (Vavassori §4.2.1):
//              G(v) = mu exp(lambda (v.p - 1)); shape (lambda, log mu)
//   sg_free    the same with p free on the sphere (a Ceres SphereManifold)
//   dexp_paper the double exponential as the paper estimates it, in four steps and without a
//              solve (Vavassori §4.2.2, steps 1-4; step 2 on rings, double_exponential_estimate):
//              the estimate behind Figs. 4.9 and 4.10
//   dexp       double exponential (Vavassori §4.2.2): L = alpha exp(beta e^{gamma sqrt(1 - p.w)});
//              p free. Fitted as log L = a + b (e^{gamma s} - 1) / gamma, s = sqrt(1 - p.w), with
//              a = log alpha + beta (log L at the peak) and b = beta gamma (its slope in s there):
//              the same lobes, but where log L is straight in s the paper's (alpha, beta) run off
//              to (0, infinity) with beta gamma fixed, while (a, b, gamma) stay finite with
//              gamma -> 0. shape (a, b, gamma)
//   adexp      anisotropic double exponential (this project, beyond §4.2): 1 - p.w = |w - p|^2 / 2
//              is split along the two tangents of p, one in the lobe's plane of symmetry
//              (phi = 0) and one across it, and the two are scaled by e^{eta} and e^{-eta}: a lobe
//              flattened across the plane (Figs. 4.6, 4.10) has eta < 0. eta = 0 is dexp. shape
//              (a, b, gamma, eta), p free.
//   asg        anisotropic spherical Gaussian (Xu et al. 2013, §3, the ASG definition):
//              c max(v.z, 0) exp(-lambda (v.x)^2 - mu (v.y)^2) with z = p, x the tangent in the
//              plane of symmetry and y the one across it (a lobe mirror-symmetric about phi = 0
//              has its frame there, so the ASG's rotation about z is not fitted). shape
//              (log c, lambda, mu).
//   adexp_ridge adexp plus the ridge of once-scattered light along the phi = 0 plane (this
//              project): near the source most of a lobe is light scattered once out of the beam,
//              and every such photon comes from the beam line, which lies in the plane through
//              the bin and the axis: a line on the sphere of directions, phi = 0 exactly, that no
//              lobe of finite width can follow (adexp runs its eta to the bound chasing it). The
//              ridge is a line density R(theta) (ridge.hpp gives its form and derivation); its
//              amplitude is c e^{a}, c >= 0 linear, so that c = 0 is adexp exactly.
//   adexp2_ridge adexp_ridge plus a second adexp of its own axis and shape (this project): near
//              the beam, beyond a mean free path, the multiply scattered light is a forward cone
//              about the beam beside the light spreading from the ridge, two lobes that one
//              adexp cannot both follow. shape and second_shape as adexp's.
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

#include "scatterlab/fit/lobe_grid.hpp"
#include "scatterlab/fit/ridge.hpp"

namespace scatterlab::fit {

enum class LobeModel { sg, sg_free, dexp_paper, dexp, adexp, asg, adexp_ridge, adexp2_ridge };

// In the order the fits run: each model may start from an earlier one's solution.
inline constexpr std::array<LobeModel, 8> kAllLobeModels = {
    LobeModel::sg,    LobeModel::sg_free, LobeModel::dexp_paper,  LobeModel::dexp,
    LobeModel::adexp, LobeModel::asg,     LobeModel::adexp_ridge, LobeModel::adexp2_ridge};

// "sg", "sg_free", "dexp_paper", "dexp", "adexp", "asg", "adexp_ridge", "adexp2_ridge".
std::string to_string(LobeModel model);
// Throws InputError("models", ...) for an unknown name.
LobeModel parse_lobe_model(const std::string& name);
// Comma-separated list, e.g. "sg,dexp"; throws InputError("models", ...).
std::vector<LobeModel> parse_lobe_models(const std::string& list);
// One line: the formula and where it comes from.
std::string describe(LobeModel model);

// The parameters a Ceres problem moves: the axis and up to four shape parameters, for
// adexp_ridge and adexp2_ridge the ridge's seven (c, g, k, theta_on, width, c_spread, kappa;
// ridge.hpp), and for adexp2_ridge the second lobe's axis and shape.
struct LobeParameters {
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  std::array<double, 4> shape{};
  std::array<double, 7> ridge{};
  Eigen::Vector3d second_axis = Eigen::Vector3d::UnitZ();
  std::array<double, 4> second_shape{};
};

// Parameters a fit moves: shape parameters plus 2 for a free axis (per axis).
int free_parameters(LobeModel model);

// (a, b, gamma, eta) of the double exponentials from Vavassori's (log alpha, beta, gamma).
std::array<double, 4> double_exponential_shape(double log_alpha, double beta, double gamma,
                                               double eta = 0.0);

// What users see, in order: the model's parameters as the papers write them (for the double
// exponentials also a = log_peak and b = slope), then p.
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

template <typename T, typename U>
T dot(const T* axis, const U* w) {
  return axis[0] * w[0] + axis[1] * w[1] + axis[2] * w[2];
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

// log(e^a + e^b), kept relative to the larger so that neither overflows.
template <typename T>
T log_add_exp(const T& a, const T& b) {
  using std::exp;
  using std::log1p;
  return a > b ? a + log1p(exp(b - a)) : b + log1p(exp(a - b));
}

// (e^{gamma s} - 1) / gamma, continuous through gamma = 0 (where it is s).
template <typename T>
T exp_ramp(const T& gamma, const T& s) {
  using std::abs;
  using std::expm1;
  if (abs(gamma) > T(1e-6)) return expm1(gamma * s) / gamma;
  return s * (T(1) + gamma * s * (T(0.5) + gamma * s / T(6)));
}

// The tangents of p that the plane of symmetry singles out: t2 = the unit tangent across the
// plane (along e_phi, or along e_r when p lies on the e_phi axis) and t1 = t2 x p in the plane.
template <typename T>
void symmetry_tangents(const T* axis, T* t1, T* t2) {
  using std::sqrt;
  // t2 = (e - (e.p) p) / |...| for e = e_phi, or e_r when p is (nearly) along e_phi.
  const int k = axis[1] * axis[1] > T(1.0 - 1e-9) ? 0 : 1;
  const T norm = sqrt(T(1) - axis[k] * axis[k]);
  for (int i = 0; i < 3; ++i) t2[i] = -axis[k] * axis[i];
  t2[k] += T(1);
  for (int i = 0; i < 3; ++i) t2[i] /= norm;
  t1[0] = t2[1] * axis[2] - t2[2] * axis[1];
  t1[1] = t2[2] * axis[0] - t2[0] * axis[2];
  t1[2] = t2[0] * axis[1] - t2[1] * axis[0];
}

}  // namespace detail

// Each model is an Evaluator built once per parameter set (what depends on p and the shape
// alone is computed there, not per direction) with log_value(w); the static log_value is the
// one-off form.

// Vavassori §4.2.1, the SG: log G = log mu + lambda (v.p - 1). shape = (lambda, log mu).
struct SphericalGaussian {
  static constexpr int kShape = 2;
  template <typename T>
  class Evaluator {
   public:
    Evaluator(const T* axis, const T* shape) : axis_(axis), shape_(shape) {}
    T log_value(const Eigen::Vector3d& w) const {
      return shape_[1] + shape_[0] * (detail::dot(axis_, w) - T(1));
    }

   private:
    const T* axis_;
    const T* shape_;
  };
  template <typename T>
  static T log_value(const T* axis, const T* shape, const Eigen::Vector3d& w) {
    return Evaluator<T>(axis, shape).log_value(w);
  }
};

// Vavassori §4.2.2: log L = log alpha + beta exp(gamma sqrt(1 - p.w)), written as
// a + b (e^{gamma s} - 1) / gamma (see the top of this file). shape = (a, b, gamma).
struct DoubleExponential {
  static constexpr int kShape = 3;
  template <typename T>
  class Evaluator {
   public:
    Evaluator(const T* axis, const T* shape) : axis_(axis), shape_(shape) {}
    T log_value(const Eigen::Vector3d& w) const {
      return shape_[0] + shape_[1] * detail::exp_ramp(shape_[2], detail::half_chord(axis_, w));
    }

   private:
    const T* axis_;
    const T* shape_;
  };
  template <typename T>
  static T log_value(const T* axis, const T* shape, const Eigen::Vector3d& w) {
    return Evaluator<T>(axis, shape).log_value(w);
  }
};

// The anisotropic double exponential: sqrt(1 - p.w) replaced by
//   s_eta = sqrt((e^{eta} (w.t1)^2 + e^{-eta} (w.t2)^2 + (1 - w.p)^2) / 2),
// with (t1, t2) the symmetry tangents of p. For eta = 0 the sum is
// (w.t1)^2 + (w.t2)^2 + (1 - w.p)^2 = |w - p|^2, so s_0 = sqrt(1 - p.w).
// shape = (a, b, gamma, eta) as for DoubleExponential.
struct AnisotropicDoubleExponential {
  static constexpr int kShape = 4;
  template <typename T>
  class Evaluator {
   public:
    Evaluator(const T* axis, const T* shape) : axis_(axis), shape_(shape) {
      using std::exp;
      detail::symmetry_tangents(axis, t1_, t2_);
      along_scale_ = T(0.5) * exp(shape[3]);
      across_scale_ = T(0.5) * exp(-shape[3]);
    }
    // The argument of the ramp, s_eta(w).
    T distance(const Eigen::Vector3d& w) const {
      const T along_plane = detail::dot(t1_, w), across_plane = detail::dot(t2_, w);
      const T radial = T(1) - detail::dot(axis_, w);
      return detail::sqrt_zero_safe(along_scale_ * along_plane * along_plane +
                                    across_scale_ * across_plane * across_plane +
                                    T(0.5) * radial * radial);
    }
    T log_value(const Eigen::Vector3d& w) const {
      return shape_[0] + shape_[1] * detail::exp_ramp(shape_[2], distance(w));
    }

   private:
    const T* axis_;
    const T* shape_;
    T t1_[3], t2_[3], along_scale_, across_scale_;
  };
  template <typename T>
  static T log_value(const T* axis, const T* shape, const Eigen::Vector3d& w) {
    return Evaluator<T>(axis, shape).log_value(w);
  }
};

// Xu et al. 2013, §3 (the ASG): G(v) = c S(v; z) exp(-lambda (v.x)^2 - mu (v.y)^2) with the
// smooth term S(v; z) = max(v.z, 0); z = p, (x, y) = the symmetry tangents (t1, t2).
// shape = (log c, lambda, mu). Where v.z <= 0 the ASG is 0: log G is returned as log c - 1000
// there (e^{-1000} is 0 in double) with no dependence on p, so that neither log 0 nor the
// unbounded derivative of log(v.z) at v.z = 0 reach a Jacobian.
struct AnisotropicSphericalGaussian {
  static constexpr int kShape = 3;
  static constexpr double kSmoothCut = 1e-12;
  template <typename T>
  class Evaluator {
   public:
    Evaluator(const T* axis, const T* shape) : axis_(axis), shape_(shape) {
      detail::symmetry_tangents(axis, x_, y_);
    }
    T log_value(const Eigen::Vector3d& w) const {
      using std::log;
      const T along = detail::dot(axis_, w);
      if (!(along > T(kSmoothCut))) return shape_[0] - T(1000.0);
      const T vx = detail::dot(x_, w), vy = detail::dot(y_, w);
      return shape_[0] + log(along) - shape_[1] * vx * vx - shape_[2] * vy * vy;
    }

   private:
    const T* axis_;
    const T* shape_;
    T x_[3], y_[3];
  };
  template <typename T>
  static T log_value(const T* axis, const T* shape, const Eigen::Vector3d& w) {
    return Evaluator<T>(axis, shape).log_value(w);
  }
};

// adexp plus the once-scattered ridge (ridge.hpp): the smooth part is the adexp of (axis,
// shape), averaged over a bin by its nodes; the ridge, a line on phi = 0, by its own nodes
// (LobeGrid::ridge_nodes); the ridge's spread by the bin's nodes. ridge = (c, g, k, theta_on,
// w, c_spread, kappa) with A = c e^{a} and A_spread = c_spread e^{a}.
struct AnisotropicRidge {
  static constexpr int kShape = 4;
  static constexpr int kRidge = 7;
  template <typename T>
  class Evaluator {
   public:
    Evaluator(const T* axis, const T* shape, const T* ridge, const LobeGrid& grid)
        : lobe_(axis, shape), log_peak_(shape[0]), ridge_(ridge) {
      prepare(grid);
    }
    T log_value(const Eigen::Vector3d& w) const { return lobe_.log_value(w); }
    // R(theta), the ridge's density across the line.
    T ridge_density(double theta) const {
      using std::exp;
      return ridge_[0] * exp(log_peak_ + log_ridge_profile(ridge_, theta));
    }
    // The spread ridge (ridge.hpp), A_spread R(theta)/A e^{kappa (cos phi - 1)}: a product of a
    // function of theta and one of phi, averaged over a bin as a product of its row's and
    // column's averages (LobeGrid::row_nodes), computed once per parameter set.
    T spread_average(std::size_t theta_bin, std::size_t phi_bin) const {
      return row_[theta_bin] * column_[phi_bin];
    }

   private:
    void prepare(const LobeGrid& grid) {
      using std::exp;
      row_.assign(grid.theta_bins(), T(0.0));
      column_.assign(grid.phi_bins(), T(0.0));
      for (std::size_t t = 0; t < grid.theta_bins(); ++t) {
        for (const FactorNode& node : grid.row_nodes(t)) {
          row_[t] += node.weight * exp(log_peak_ + log_ridge_profile(ridge_, node.value));
        }
        row_[t] *= ridge_[5];
      }
      for (std::size_t f = 0; f < grid.phi_bins(); ++f) {
        for (const FactorNode& node : grid.column_nodes(f)) {
          column_[f] += node.weight * exp(ridge_[6] * (node.value - 1.0));
        }
      }
    }
    typename AnisotropicDoubleExponential::template Evaluator<T> lobe_;
    T log_peak_;
    const T* ridge_;
    std::vector<T> row_, column_;
  };
};

// adexp_ridge plus a second adexp of its own axis and shape: near the source, where the
// multiply scattered light is not one lobe (a forward cone about the beam beside the light
// spreading from the ridge), the second lobe takes what the first leaves.
struct TwoLobeRidge {
  template <typename T>
  class Evaluator {
   public:
    Evaluator(const T* axis, const T* shape, const T* ridge, const LobeGrid& grid,
              const T* second_axis, const T* second_shape)
        : first_(axis, shape, ridge, grid), second_(second_axis, second_shape) {}
    T log_value(const Eigen::Vector3d& w) const {
      return detail::log_add_exp(first_.log_value(w), second_.log_value(w));
    }
    T ridge_density(double theta) const { return first_.ridge_density(theta); }
    T spread_average(std::size_t theta_bin, std::size_t phi_bin) const {
      return first_.spread_average(theta_bin, phi_bin);
    }

   private:
    AnisotropicRidge::Evaluator<T> first_;
    AnisotropicDoubleExponential::Evaluator<T> second_;
  };
};

// log of the model at one direction, for doubles (tests, errors, estimates); for the ridge
// models the smooth part (the ridge is a line: it has a density across it, not a value).
double log_model_value(LobeModel model, const LobeParameters& parameters,
                       const Eigen::Vector3d& direction);

}  // namespace scatterlab::fit
