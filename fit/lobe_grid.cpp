#include "scatterlab/fit/lobe_grid.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "scatterlab/core/constants.hpp"
#include "scatterlab/core/quadrature.hpp"

namespace scatterlab::fit {

namespace {

Eigen::Vector3d direction(double cos_theta, double phi) {
  const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
  return {sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta};
}

void check_edges(std::span<const double> edges, double upper, const char* name) {
  if (edges.size() < 2) throw std::invalid_argument(std::string(name) + ": fewer than 2 edges");
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const bool ordered = i == 0 || edges[i] > edges[i - 1];
    if (!ordered || !(edges[i] >= -1e-12 && edges[i] <= upper + 1e-12)) {
      throw std::invalid_argument(std::string(name) + ": edges must increase within [0, " +
                                  std::to_string(upper) + "]");
    }
  }
}

}  // namespace

LobeGrid::LobeGrid(std::span<const double> theta_edges, std::span<const double> phi_edges,
                   bool phi_folded, int quadrature_order)
    : theta_bins_(theta_edges.size() - 1),
      phi_bins_(phi_edges.size() - 1),
      phi_folded_(phi_folded),
      quadrature_order_(quadrature_order) {
  check_edges(theta_edges, pi, "theta");
  check_edges(phi_edges, phi_folded ? pi : 2.0 * pi, "phi");
  if (quadrature_order < 1 || quadrature_order > 8) {
    throw std::invalid_argument("quadrature order must be in [1, 8]");
  }
  const GaussLegendre rule = gauss_legendre(quadrature_order);
  const std::size_t n = rule.nodes.size();
  const std::size_t mirrors = phi_folded ? 2 : 1;
  nodes_per_bin_ = n * n * mirrors;
  const double plane_tolerance = 1e-9;
  // The bin nodes are a product rule: (mu_i, phi_j) with weight (w_i / 2) (w_j / 2). Its factors
  // per row and column, for models that are a product of a function of theta and one of phi.
  for (std::size_t t = 0; t < theta_bins_; ++t) {
    const double mu_low = std::cos(theta_edges[t + 1]), mu_high = std::cos(theta_edges[t]);
    for (std::size_t i = 0; i < n; ++i) {
      const double mu = 0.5 * (mu_low + mu_high) + 0.5 * (mu_high - mu_low) * rule.nodes[i];
      row_nodes_.push_back({std::acos(std::clamp(mu, -1.0, 1.0)), 0.5 * rule.weights[i]});
    }
  }
  for (std::size_t f = 0; f < phi_bins_; ++f) {
    const double phi_low = phi_edges[f], phi_high = phi_edges[f + 1];
    for (std::size_t j = 0; j < n; ++j) {
      const double phi = 0.5 * (phi_low + phi_high) + 0.5 * (phi_high - phi_low) * rule.nodes[j];
      column_nodes_.push_back({std::cos(phi), 0.5 * rule.weights[j]});
    }
  }
  for (std::size_t t = 0; t < theta_bins_; ++t) {
    // cos theta decreases with theta: integrate over [cos t1, cos t0].
    const double mu_low = std::cos(theta_edges[t + 1]), mu_high = std::cos(theta_edges[t]);
    for (std::size_t f = 0; f < phi_bins_; ++f) {
      const double phi_low = phi_edges[f], phi_high = phi_edges[f + 1];
      solid_angles_.push_back((mu_high - mu_low) * (phi_high - phi_low));
      centres_.push_back(direction(std::cos(0.5 * (theta_edges[t] + theta_edges[t + 1])),
                                   0.5 * (phi_low + phi_high)));
      in_plane_.push_back(phi_low < plane_tolerance || std::abs(phi_high - pi) < plane_tolerance ||
                          std::abs(phi_low - pi) < plane_tolerance ||
                          std::abs(phi_high - 2.0 * pi) < plane_tolerance);
      // The line phi = 0 (ridge.hpp): half of it in each of the two bins beside it, or all of
      // it, with its mirror image, in the one bin of a folded grid: 1 / (2 Omega) either way.
      const bool on_ridge =
          phi_low < plane_tolerance || std::abs(phi_high - 2.0 * pi) < plane_tolerance;
      on_ridge_.push_back(on_ridge);
      const double theta_low = theta_edges[t], theta_high = theta_edges[t + 1];
      for (std::size_t i = 0; i < n; ++i) {
        const double half_width = 0.5 * (theta_high - theta_low);
        ridge_nodes_.push_back(
            {0.5 * (theta_low + theta_high) + half_width * rule.nodes[i],
             on_ridge ? half_width * rule.weights[i] / (2.0 * solid_angles_.back()) : 0.0});
      }
      for (std::size_t i = 0; i < n; ++i) {
        const double mu = 0.5 * (mu_low + mu_high) + 0.5 * (mu_high - mu_low) * rule.nodes[i];
        for (std::size_t j = 0; j < n; ++j) {
          const double phi =
              0.5 * (phi_low + phi_high) + 0.5 * (phi_high - phi_low) * rule.nodes[j];
          const double weight =
              0.25 * rule.weights[i] * rule.weights[j] / static_cast<double>(mirrors);
          nodes_.push_back({direction(mu, phi), weight});
          if (phi_folded) nodes_.push_back({direction(mu, -phi), weight});
        }
      }
    }
  }
}

}  // namespace scatterlab::fit
