#pragma once
// The angular grid of a radiance lobe, as the fits see it: per (theta, phi) bin its centre
// direction, its solid angle, and quadrature nodes that average a model over the bin.
//
// Directions are in the local frame of the spatial bin, (e_r, e_phi, e_z) with
// omega = (sin t cos f, sin t sin f, cos t). The tally stores bin
// averages, so a model is compared with its own average over each bin, not its value at the
// centre: on the paper's 10-degree bins a lobe with lambda ~ 1e3 (width ~2 degrees) lives inside
// one bin, and its centre value says nothing about its bin average. The average is an n x n
// Gauss-Legendre rule in (cos theta, phi), exact for the measure d omega = d(cos t) d phi. On a
// folded grid (phi in [0, pi]) each bin also holds the mirror image phi -> -phi, so every node
// has a mirrored twin of half the weight.

#include <Eigen/Core>
#include <cstddef>
#include <span>
#include <vector>

namespace scatterlab::fit {

struct LobeNode {
  Eigen::Vector3d direction;
  double weight = 0.0;  // weights of one bin's nodes sum to 1
};

// One factor of the product rule: theta (or cos phi) and half its Gauss-Legendre weight, so
// that a function f(theta) g(phi) averages over bin (t, f) to
// (sum over row t of weight f(theta)) (sum over column f of weight g(phi)).
struct FactorNode {
  double value = 0.0;
  double weight = 0.0;  // the weights of one row (column) sum to 1
};

// A node of the quadrature that averages a line density R(theta) on phi = 0 over a bin
// (ridge.hpp): <L>_bin = sum weight R(theta).
struct RidgeNode {
  double theta = 0.0;
  double weight = 0.0;  // (d theta weight of Gauss-Legendre) / (2 Omega_bin)
};

class LobeGrid {
 public:
  // `theta_edges` in [0, pi], `phi_edges` in [0, pi] (folded) or [0, 2 pi], increasing.
  // Throws std::invalid_argument for edges that are not increasing or out of range, or a
  // quadrature order outside [1, 8].
  LobeGrid(std::span<const double> theta_edges, std::span<const double> phi_edges, bool phi_folded,
           int quadrature_order = 3);

  std::size_t theta_bins() const { return theta_bins_; }
  std::size_t phi_bins() const { return phi_bins_; }
  std::size_t size() const { return theta_bins_ * phi_bins_; }  // bin = theta * phi_bins + phi
  bool phi_folded() const { return phi_folded_; }
  int quadrature_order() const { return quadrature_order_; }

  const Eigen::Vector3d& centre(std::size_t bin) const { return centres_[bin]; }
  double solid_angle(std::size_t bin) const { return solid_angles_[bin]; }
  // Nodes of one bin: nodes_per_bin() consecutive entries.
  std::span<const LobeNode> nodes(std::size_t bin) const {
    return {nodes_.data() + bin * nodes_per_bin_, nodes_per_bin_};
  }
  std::size_t nodes_per_bin() const { return nodes_per_bin_; }
  // Nodes of the line phi = 0 in one bin: quadrature_order() of them for a bin whose phi range
  // ends at phi = 0 or 2 pi, none for the others.
  std::span<const RidgeNode> ridge_nodes(std::size_t bin) const {
    const std::size_t n = on_ridge_[bin] ? static_cast<std::size_t>(quadrature_order_) : 0;
    return {ridge_nodes_.data() + bin * static_cast<std::size_t>(quadrature_order_), n};
  }
  // The product rule's factors: quadrature_order() nodes per theta row (theta) and per phi
  // column (cos phi; a folded grid's mirror image -phi has the same cosine).
  std::span<const FactorNode> row_nodes(std::size_t theta_bin) const {
    const auto n = static_cast<std::size_t>(quadrature_order_);
    return {row_nodes_.data() + theta_bin * n, n};
  }
  std::span<const FactorNode> column_nodes(std::size_t phi_bin) const {
    const auto n = static_cast<std::size_t>(quadrature_order_);
    return {column_nodes_.data() + phi_bin * n, n};
  }
  // Bins that touch the phi = 0 half-plane or its continuation phi = pi: the cut through the
  // lobe's plane of symmetry that Vavassori's Figs. 4.5, 4.8 and 4.10 show.
  bool in_symmetry_plane(std::size_t bin) const { return in_plane_[bin]; }

 private:
  std::size_t theta_bins_ = 0, phi_bins_ = 0, nodes_per_bin_ = 0;
  bool phi_folded_ = false;
  int quadrature_order_ = 0;
  std::vector<Eigen::Vector3d> centres_;
  std::vector<double> solid_angles_;
  std::vector<LobeNode> nodes_;
  std::vector<bool> in_plane_;
  std::vector<FactorNode> row_nodes_, column_nodes_;
  std::vector<RidgeNode> ridge_nodes_;  // quadrature_order per bin, zero weights off the line
  std::vector<bool> on_ridge_;
};

}  // namespace scatterlab::fit
