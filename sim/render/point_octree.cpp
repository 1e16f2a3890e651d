#include "scatterlab/render/point_octree.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "scatterlab/core/error.hpp"
#include "scatterlab/render/point_cloud.hpp"

namespace scatterlab {

namespace {

std::vector<double> profile_at(const DiffusionProfile& profile, std::span<const double> r) {
  std::vector<double> values(r.size());
  for (std::size_t k = 0; k < r.size(); ++k) values[k] = profile.reflectance(r[k]);
  return values;
}

}  // namespace

std::vector<double> RadialKernel::node_radii(double rho, double r_max, int nodes) {
  if (!(rho > 0.0) || !(r_max > rho) || !std::isfinite(r_max) || nodes < 2) {
    throw InputError("points",
                     fmt::format("a point radius {} and a largest distance {}", rho, r_max),
                     "points smaller than the mesh (a point radius below its size)");
  }
  const double step = (std::log(r_max) - std::log(rho)) / (nodes - 1);
  std::vector<double> r(static_cast<std::size_t>(nodes));
  for (int k = 0; k < nodes; ++k)
    r[static_cast<std::size_t>(k)] = std::exp(std::log(rho) + k * step);
  return r;
}

RadialKernel::RadialKernel(const DiffusionProfile& profile, double rho, double r_max, int nodes)
    : RadialKernel(profile_at(profile, node_radii(rho, r_max, nodes)),
                   profile.annulus_averages(std::array<double, 2>{0.0, rho})[0], rho, r_max) {}

RadialKernel::RadialKernel(std::span<const double> values_at_nodes, double disc_average, double rho,
                           double r_max)
    : rho_(rho), log_rho_(std::log(rho)), disc_average_(disc_average) {
  const int nodes = static_cast<int>(values_at_nodes.size());
  if (!(rho > 0.0) || !(r_max > rho) || !std::isfinite(r_max) || nodes < 2) {
    throw InputError("points",
                     fmt::format("a point radius {} and a largest distance {}", rho, r_max),
                     "points smaller than the mesh (a point radius below its size)");
  }
  if (!std::isfinite(disc_average)) {
    throw InputError("model", fmt::format("R_d's average within r = {} is {}", rho, disc_average),
                     "a profile finite for r > 0 whose r R_d(r) is integrable at 0");
  }
  const double step = (std::log(r_max) - log_rho_) / (nodes - 1);
  inverse_step_ = 1.0 / step;
  last_ = static_cast<double>(nodes - 1);
  log_values_.resize(static_cast<std::size_t>(nodes) + 1);
  for (std::size_t k = 0; k < values_at_nodes.size(); ++k) {
    const double value = values_at_nodes[k];
    if (!std::isfinite(value)) {
      throw InputError("model", fmt::format("R_d is {} at node {}", value, k),
                       "a profile finite for r > 0");
    }
    log_values_[k] = std::log(std::max(value, 1e-300));
  }
  // operator() reads node k + 1 at s = last_ (f = 0): a copy of the last node.
  log_values_.back() = log_values_[log_values_.size() - 2];
}

PointOctree::PointOctree(std::span<const Vec3> positions, std::span<const double> power,
                         double point_area)
    : positions_(positions.begin(), positions.end()),
      power_(power.begin(), power.end()),
      point_area_(point_area) {
  if (positions.size() != power.size() || positions.empty()) {
    throw std::invalid_argument("PointOctree: one power per point, and at least one point");
  }
  nodes_.push_back({});
  build(0, 0, static_cast<std::uint32_t>(positions_.size()), 1);
}

void PointOctree::build(std::uint32_t node, std::uint32_t begin, std::uint32_t end, int depth) {
  depth_ = std::max(depth_, depth);
  Node n;
  n.box = {positions_[begin], positions_[begin]};
  Vec3 centre = Vec3::Zero(), weighted = Vec3::Zero();
  for (std::uint32_t i = begin; i < end; ++i) {
    n.box.lo = n.box.lo.cwiseMin(positions_[i]);
    n.box.hi = n.box.hi.cwiseMax(positions_[i]);
    centre += positions_[i];
    weighted += power_[i] * positions_[i];
    n.power += power_[i];
  }
  const std::uint32_t count = end - begin;
  centre /= static_cast<double>(count);
  n.area = point_area_ * count;
  // Jensen & Buhler's irradiance-weighted location (Bitterli §2.6.4, P_v of eq. 2.40).
  n.mean = n.power > 0.0 ? Vec3(weighted / n.power) : n.box.center();
  n.first = begin;
  n.count = count;
  n.leaf = true;
  // Split about the mean position into octants (Bitterli §3.3.1), by a counting sort.
  if (count > static_cast<std::uint32_t>(max_leaf_points) && depth < max_depth) {
    std::vector<std::uint8_t> octant(count);
    std::array<std::uint32_t, 9> start{};
    for (std::uint32_t i = begin; i < end; ++i) {
      const Vec3& p = positions_[i];
      const int o = (p.x() > centre.x() ? 1 : 0) | (p.y() > centre.y() ? 2 : 0) |
                    (p.z() > centre.z() ? 4 : 0);
      octant[i - begin] = static_cast<std::uint8_t>(o);
      ++start[static_cast<std::size_t>(o) + 1];
    }
    const int occupied = static_cast<int>(
        std::count_if(start.begin() + 1, start.end(), [](auto c) { return c > 0; }));
    if (occupied > 1) {  // one octant only: every point at the same place, a leaf
      for (int o = 0; o < 8; ++o) start[o + 1] += start[o];
      std::vector<Vec3> p(count);
      std::vector<double> e(count);
      std::array<std::uint32_t, 9> fill = start;
      for (std::uint32_t i = 0; i < count; ++i) {
        const std::uint32_t to = fill[octant[i]]++;
        p[to] = positions_[begin + i];
        e[to] = power_[begin + i];
      }
      std::copy(p.begin(), p.end(), positions_.begin() + begin);
      std::copy(e.begin(), e.end(), power_.begin() + begin);
      n.leaf = false;
      n.first = static_cast<std::uint32_t>(nodes_.size());
      n.count = static_cast<std::uint32_t>(occupied);
      for (int o = 0; o < occupied; ++o) nodes_.push_back({});
      nodes_[node] = n;
      std::uint32_t child = n.first;
      for (int o = 0; o < 8; ++o) {
        if (start[o + 1] == start[o]) continue;
        build(child++, begin + start[o], begin + start[o + 1], depth + 1);
      }
      return;
    }
  }
  nodes_[node] = n;
}

void PointOctree::sum_points(const Vec3& x, std::uint32_t begin, std::uint32_t end,
                             std::span<const RadialKernel> kernels,
                             std::span<double> exitance) const {
  const std::size_t channels = kernels.size();
  for (std::uint32_t i = begin; i < end; ++i) {
    const RadialKernel::Place place = kernels[0].locate((x - positions_[i]).norm());
    const double power = power_[i];
    for (std::size_t c = 0; c < channels; ++c) exitance[c] += power * kernels[c].at(place);
  }
}

PointOctree cloud_octree(const PointCloud& cloud, std::span<const double> irradiance) {
  std::vector<double> power(cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) power[i] = irradiance[i] * cloud.point_area;
  return PointOctree(cloud.positions, power, cloud.point_area);
}

KernelGrid cloud_kernel_grid(double point_area, const BoundingBox& bounds) {
  const double rho = std::sqrt(point_area / std::numbers::pi);
  return {rho, 1.01 * bounds.diagonal() + 2.0 * rho};
}

std::vector<RadialKernel> cloud_kernels(std::span<const DiffusionProfile> profiles,
                                        double point_area, const BoundingBox& bounds) {
  const KernelGrid grid = cloud_kernel_grid(point_area, bounds);
  std::vector<RadialKernel> kernels;
  kernels.reserve(profiles.size());
  for (const DiffusionProfile& profile : profiles)
    kernels.emplace_back(profile, grid.rho, grid.r_max);
  return kernels;
}

namespace {

void check_kernels(std::span<const RadialKernel> kernels, std::span<double> exitance) {
  if (kernels.empty() || kernels.size() > max_kernel_channels || exitance.size() < kernels.size() ||
      !std::all_of(kernels.begin(), kernels.end(),
                   [&](const RadialKernel& k) { return k.same_grid(kernels[0]); })) {
    throw std::invalid_argument("PointOctree: 1 to 3 kernels on one grid, an output for each");
  }
}

}  // namespace

void PointOctree::exitance(const Vec3& x, double epsilon, std::span<const RadialKernel> kernels,
                           std::span<double> exitance, OctreeQuery& query) const {
  check_kernels(kernels, exitance);
  const std::size_t channels = kernels.size();
  for (std::size_t c = 0; c < channels; ++c) exitance[c] = 0.0;
  // Depth first, children in order (pushed last to first), so that the leaves are summed in the
  // order of the point array: with epsilon = 0 the sum is unclustered_exitance's, bit for bit.
  std::array<std::uint32_t, 8 * max_depth + 8> stack;
  std::size_t top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (node.power == 0.0) continue;
    // Squared distance from x to the node's box (0 inside it).
    const Vec3 outside =
        (node.box.lo - x).cwiseMax(Vec3::Zero()) + (x - node.box.hi).cwiseMax(Vec3::Zero());
    const double d2 = outside.squaredNorm();
    if (node.area < epsilon * d2) {  // Delta omega = A_v / d^2 < epsilon (eq. 2.40, box distance)
      const RadialKernel::Place place = kernels[0].locate((x - node.mean).norm());
      for (std::size_t c = 0; c < channels; ++c) exitance[c] += node.power * kernels[c].at(place);
      ++query.evaluations;
      ++query.clusters;
    } else if (node.leaf) {
      sum_points(x, node.first, node.first + node.count, kernels, exitance);
      query.evaluations += node.count;
    } else {
      for (std::uint32_t k = node.count; k-- > 0;) stack[top++] = node.first + k;
    }
  }
}

void PointOctree::unclustered_exitance(const Vec3& x, std::span<const RadialKernel> kernels,
                                       std::span<double> exitance, OctreeQuery& query) const {
  check_kernels(kernels, exitance);
  for (std::size_t c = 0; c < kernels.size(); ++c) exitance[c] = 0.0;
  sum_points(x, 0, static_cast<std::uint32_t>(positions_.size()), kernels, exitance);
  query.evaluations += positions_.size();
}

}  // namespace scatterlab
