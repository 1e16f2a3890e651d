#pragma once
// The second pass of the hierarchical evaluation (Jensen & Buhler 2002; Bitterli 2013, §2.6.4
// "Second Pass: BSSRDF Evaluation", §3.3.1, §3.3.3): the exitance of multiple scattering at a
// surface point x_o from a point cloud with the power E_t(p) A_p entering at each point p
// (point_cloud.hpp),
//   M(x_o) = sum_p E_t(p) A_p R_d(|x_o - p|)                                   (Bitterli eq. 2.15
// summed over the cloud: the area integral of eq. 2.14 with S_d's exit factor taken out),
// in W / length^2 for E_t in W / length^2 and R_d in 1 / length^2 per unit power entering.
//
// The octree (Bitterli §3.3.1): the root holds every point; a node splits its points into the
// octants about their mean position (a counting sort, so each child's points are one range of
// the point array) until it holds 8 or fewer. Each node keeps the total area A_v of its points,
// their total power P_v = sum E_t A_p, the power-weighted mean position X_v (Jensen & Buhler's
// irradiance-weighted location; with equal areas the same thing) and the bounding box of its
// points.
//
// Traversal (Bitterli Algorithm 2): from the root, a node is evaluated as one point, P_v
// R_d(|x_o - X_v|), when the solid angle it subtends is small, Delta omega < epsilon (eq. 2.40);
// otherwise its children are visited, and a leaf's points are summed one by one. Eq. 2.40
// divides A_v by the squared distance to X_v, which overestimates the distance to a node whose
// points are spread (Bitterli §2.6.4 notes it); here the distance is that to the node's bounding
// box, which never exceeds the distance to any of its points (Bitterli's conservative choice):
//   Delta omega = A_v / dist(x_o, box_v)^2, clustered when A_v < epsilon dist^2.
// A node that holds x_o (distance 0) is always opened, and epsilon = 0 opens every node: the sum
// is then the unclustered one, in the same order, bit for bit (unclustered_exitance). Nodes
// without power are skipped (their terms are exact zeros).
//
// R_d is read from a table (RadialKernel) per channel, so that every model costs the same in the
// loop, which allocates nothing and calls nothing virtual.

#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "scatterlab/core/triangle_mesh.hpp"
#include "scatterlab/models/diffusion_profile.hpp"

namespace scatterlab {

// R_d(r) of one profile for r in [0, r_max], tabulated at `nodes` points geometric in r from
// rho to r_max and interpolated linearly in (ln r, ln R_d): the exponential tail e^{-sigma_tr r}
// / r^k is a curve of small curvature there (the interpolation's relative error is at most
// (h^2 / 8) max |d^2 ln R_d / d (ln r)^2| ~ (h^2 / 8) sigma_tr r for spacing h in ln r: with
// the default 2048 nodes over six decades, h = 0.0067, below 1e-4 while sigma_tr r <= 17, where
// R_d has fallen by e^-17, and 3e-4 at sigma_tr r = 50). Below rho, the radius
// of the disc of one point's area A_p = pi rho^2, the table holds the average of R_d over that
// disc (closed form, DiffusionProfile::annulus_averages): the point that x_o lies on stands for
// the disc around it, and quantized diffusion's R_d(0) is infinite. Beyond r_max: the last node.
class RadialKernel {
 public:
  RadialKernel() = default;
  // rho > 0, r_max > rho; throws InputError("points", ...) otherwise.
  RadialKernel(const DiffusionProfile& profile, double rho, double r_max, int nodes = 2048);
  // A profile known only by its values (a text model): R_d at node_radii(rho, r_max, nodes), and
  // its average over the disc of radius rho, 2 / rho^2 int_0^rho R_d r dr. Throws
  // InputError("model", ...) where a value or the average is not finite.
  RadialKernel(std::span<const double> values_at_nodes, double disc_average, double rho,
               double r_max);
  // The table's nodes: geometric from rho to r_max.
  static std::vector<double> node_radii(double rho, double r_max, int nodes = 2048);

  // Where r falls in the table: kernels built with the same rho, r_max and nodes (one per
  // channel) share it, so a point's distance is located once for all channels.
  struct Place {
    std::size_t node = 0;
    double fraction = 0.0;
    bool inside_disc = false;
  };
  Place locate(double r) const {
    if (r < rho_) return {0, 0.0, true};
    double s = (std::log(r) - log_rho_) * inverse_step_;
    if (!(s < last_)) s = last_;  // beyond r_max (and NaN) read the last node
    const auto k = static_cast<std::size_t>(s);
    return {k, s - static_cast<double>(k), false};
  }
  double at(const Place& p) const {
    if (p.inside_disc) return disc_average_;
    const double a = log_values_[p.node], b = log_values_[p.node + 1];
    return std::exp(a + p.fraction * (b - a));
  }
  double operator()(double r) const { return at(locate(r)); }
  bool same_grid(const RadialKernel& other) const {
    return rho_ == other.rho_ && inverse_step_ == other.inverse_step_ && last_ == other.last_;
  }
  double rho() const { return rho_; }
  double disc_average() const { return disc_average_; }

 private:
  double rho_ = 1.0, log_rho_ = 0.0, inverse_step_ = 1.0, last_ = 0.0;
  double disc_average_ = 0.0;
  std::vector<double> log_values_;  // ln max(R_d, 1e-300) at the nodes, and one more
};

// Up to three channels (red, green, blue), one kernel each.
inline constexpr int max_kernel_channels = 3;

// The grid of a cloud's kernels, for points that each stand for `point_area` on a mesh inside
// `bounds`: rho the radius of one point's disc (A_p = pi rho^2), r_max past the box's diagonal
// (no two points of the mesh are farther apart).
struct KernelGrid {
  double rho = 0.0, r_max = 0.0;
};
KernelGrid cloud_kernel_grid(double point_area, const BoundingBox& bounds);

// One kernel per profile on the cloud's grid, so that the kernels share it.
std::vector<RadialKernel> cloud_kernels(std::span<const DiffusionProfile> profiles,
                                        double point_area, const BoundingBox& bounds);

struct OctreeQuery {
  std::uint64_t evaluations = 0;  // R_d lookups: points summed plus nodes clustered
  std::uint64_t clusters = 0;     // nodes evaluated as one point
};

class PointOctree {
 public:
  // positions and power (E_t A_p per point, W) of the same length; areas: each point's.
  PointOctree(std::span<const Vec3> positions, std::span<const double> power, double point_area);

  // M(x_o) per channel into exitance[0 .. kernels.size()) (overwritten), with the cluster angle
  // epsilon >= 0 (sr). The kernels (1 to max_kernel_channels) share one grid (same_grid;
  // std::invalid_argument otherwise). Thread-safe; allocates nothing.
  void exitance(const Vec3& x, double epsilon, std::span<const RadialKernel> kernels,
                std::span<double> exitance, OctreeQuery& query) const;
  // The sum over every point, in the octree's order: exitance with epsilon = 0, bit for bit.
  void unclustered_exitance(const Vec3& x, std::span<const RadialKernel> kernels,
                            std::span<double> exitance, OctreeQuery& query) const;

  std::size_t node_count() const { return nodes_.size(); }
  int depth() const { return depth_; }
  // The points in the octree's order (leaves are ranges of it), with their power.
  std::span<const Vec3> positions() const { return positions_; }
  std::span<const double> power() const { return power_; }

  struct Node {
    BoundingBox box;
    Vec3 mean = Vec3::Zero();  // power-weighted mean position (box centre when no power)
    double area = 0.0;         // A_v
    double power = 0.0;        // P_v = sum E_t A_p
    std::uint32_t first = 0;   // first child (inner node) or first point (leaf)
    std::uint32_t count = 0;   // children (inner) or points (leaf)
    bool leaf = true;
  };
  static constexpr int max_leaf_points = 8;
  static constexpr int max_depth = 40;

 private:
  void build(std::uint32_t node, std::uint32_t begin, std::uint32_t end, int depth);
  void sum_points(const Vec3& x, std::uint32_t begin, std::uint32_t end,
                  std::span<const RadialKernel> kernels, std::span<double> exitance) const;

  std::vector<Vec3> positions_;
  std::vector<double> power_;
  double point_area_ = 0.0;
  std::vector<Node> nodes_;
  int depth_ = 0;
};

struct PointCloud;

// The octree of a cloud (point_cloud.hpp) whose points receive `irradiance` (E_t, power per unit
// area entering; one per point): each point carries E_t A_p.
PointOctree cloud_octree(const PointCloud& cloud, std::span<const double> irradiance);

}  // namespace scatterlab
