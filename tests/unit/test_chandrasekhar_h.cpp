// Chandrasekhar's H-function for isotropic scattering (models/chandrasekhar_h): the closed
// integral form against the nonlinear integral equation solved independently by iteration on a
// Gauss-Legendre grid, against its moment identities, and against Chandrasekhar's value
// H(1) = 2.90781 for conservative scattering.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "scatterlab/core/error.hpp"
#include "scatterlab/core/quadrature.hpp"
#include "scatterlab/models/chandrasekhar_h.hpp"

namespace scatterlab {
namespace {

// Gauss-Legendre nodes and weights on [0, 1] (Newton on P_n from the Chebyshev guesses).
void gauss_legendre(int n, std::vector<double>& nodes, std::vector<double>& weights) {
  nodes.assign(static_cast<std::size_t>(n), 0.0);
  weights.assign(static_cast<std::size_t>(n), 0.0);
  for (int i = 0; i < n; ++i) {
    double x = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
    double derivative = 1.0;
    for (int step = 0; step < 100; ++step) {
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      derivative = n * (x * p1 - p0) / (x * x - 1.0);
      const double dx = p1 / derivative;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    nodes[static_cast<std::size_t>(i)] = 0.5 * (1.0 - x);
    weights[static_cast<std::size_t>(i)] = 1.0 / ((1.0 - x * x) * derivative * derivative);
  }
}

// Chandrasekhar's iteration of the equivalent form (1960, §35, eq. (10)):
//   1 / H(mu) = sqrt(1 - w) + (w / 2) int_0^1 mu' H(mu') / (mu + mu') dmu',
// on a Gauss grid, then the same equation evaluates H at any mu (Nystrom interpolation).
class IteratedH {
 public:
  IteratedH(double albedo, int n) : albedo_(albedo) {
    gauss_legendre(n, nodes_, weights_);
    h_.assign(nodes_.size(), 1.0);
    for (int sweep = 0; sweep < 20000; ++sweep) {
      double change = 0.0;
      std::vector<double> next(h_.size());
      for (std::size_t i = 0; i < h_.size(); ++i) {
        next[i] = at(nodes_[i]);
        change = std::max(change, std::abs(next[i] - h_[i]));
      }
      h_ = next;
      if (change < 1e-15) break;
    }
  }

  double at(double mu) const {
    double integral = 0.0;
    for (std::size_t j = 0; j < nodes_.size(); ++j) {
      integral += weights_[j] * nodes_[j] * h_[j] / (mu + nodes_[j]);
    }
    return 1.0 / (std::sqrt(1.0 - albedo_) + 0.5 * albedo_ * integral);
  }

 private:
  double albedo_;
  std::vector<double> nodes_, weights_, h_;
};

TEST(ChandrasekharH, ConservativeValueAtNormal) {
  // Chandrasekhar 1960, table of H for w = 1: H(1) = 2.90781.
  EXPECT_NEAR(chandrasekhar_h(1.0, 1.0), 2.90781, 5e-6);
  EXPECT_EQ(chandrasekhar_h(1.0, 0.0), 1.0);
  EXPECT_EQ(chandrasekhar_h(0.0, 0.7), 1.0);
}

TEST(ChandrasekharH, AgreesWithTheIntegralEquationSolvedByIteration) {
  for (double albedo : {0.2, 0.6, 0.9, 0.99, 0.999}) {
    const IteratedH iterated(albedo, 64);
    for (double mu : {0.05, 0.25, 0.5, 0.75, 1.0}) {
      EXPECT_NEAR(chandrasekhar_h(albedo, mu), iterated.at(mu), 2e-6)
          << "albedo " << albedo << ", mu " << mu;
    }
  }
}

TEST(ChandrasekharH, ZerothMomentIdentity) {
  // alpha_0 = int_0^1 H dmu = (2 / w)(1 - sqrt(1 - w)) (Chandrasekhar 1960, §37, eq. (26)).
  for (double albedo : {0.1, 0.5, 0.9, 0.99, 1.0}) {
    const auto h = [albedo](double mu) { return chandrasekhar_h(albedo, mu); };
    const double alpha0 = integrate_adaptive(h, 0.0, 1.0, {0.0, 1e-11, 200}).value;
    EXPECT_NEAR(alpha0, 2.0 / albedo * (1.0 - std::sqrt(1.0 - albedo)), 1e-9) << albedo;
  }
}

TEST(ChandrasekharH, FirstMomentIdentityWhenConservative) {
  // w = 1: alpha_1 = int_0^1 H mu dmu = 2 / sqrt(3) (Chandrasekhar 1960, §37, eq. (30)).
  const auto h = [](double mu) { return mu * chandrasekhar_h(1.0, mu); };
  EXPECT_NEAR(integrate_adaptive(h, 0.0, 1.0, {0.0, 1e-11, 200}).value, 2.0 / std::sqrt(3.0), 1e-9);
}

TEST(ChandrasekharH, SatisfiesTheOriginalEquation) {
  // H(mu) = 1 + (w / 2) mu H(mu) int_0^1 H(mu') / (mu + mu') dmu', checked pointwise.
  for (double albedo : {0.5, 0.95, 1.0}) {
    for (double mu : {0.1, 0.6, 1.0}) {
      const auto kernel = [albedo, mu](double m) { return chandrasekhar_h(albedo, m) / (mu + m); };
      const double integral = integrate_adaptive(kernel, 0.0, 1.0, {0.0, 1e-11, 200}).value;
      const double h = chandrasekhar_h(albedo, mu);
      EXPECT_NEAR(h, 1.0 + 0.5 * albedo * mu * h * integral, 1e-9) << albedo << " " << mu;
    }
  }
}

TEST(ChandrasekharH, DiffuseReflectanceOfTheHalfSpace) {
  EXPECT_NEAR(half_space_diffuse_reflectance(1.0), 1.0, 1e-15);  // nothing absorbed, all returns
  EXPECT_EQ(half_space_diffuse_reflectance(0.0), 0.0);
  double previous = 0.0;
  for (double albedo : {0.1, 0.5, 0.9, 0.99}) {
    const double r = half_space_diffuse_reflectance(albedo);
    EXPECT_GT(r, previous);
    // At least the once-scattered part (w / 2)(1 - ln 2), at most everything scattered.
    EXPECT_GT(r, 0.5 * albedo * (1.0 - std::log(2.0)));
    EXPECT_LT(r, albedo);
    previous = r;
  }
  // Grazing incidence returns more: the first collision is shallower.
  EXPECT_GT(half_space_diffuse_reflectance(0.9, 0.2), half_space_diffuse_reflectance(0.9, 1.0));
}

TEST(ChandrasekharH, RejectsOutOfRangeInput) {
  EXPECT_THROW(chandrasekhar_h(1.1, 0.5), InputError);
  EXPECT_THROW(chandrasekhar_h(-0.1, 0.5), InputError);
  EXPECT_THROW(chandrasekhar_h(0.5, 1.5), InputError);
  EXPECT_THROW(chandrasekhar_h(0.5, std::nan("")), InputError);
}

}  // namespace
}  // namespace scatterlab
