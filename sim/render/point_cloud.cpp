#include "scatterlab/render/point_cloud.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>
#include <utility>
#include <vector>

#include "scatterlab/core/error.hpp"
#include "scatterlab/core/fresnel.hpp"
#include "scatterlab/core/random.hpp"
#include "scatterlab/mesh/mesh_ray_tracer.hpp"
#include "scatterlab/render/single_scatter_renderer.hpp"

namespace scatterlab {

namespace {

// The point of triangle (a, b, c) nearest to p, as barycentrics (u, v) of b and c (Ericson 2005,
// Real-Time Collision Detection, §5.1.5: the Voronoi regions of the vertices, then the edges,
// then the face).
std::pair<double, double> closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b,
                                              const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return {0.0, 0.0};
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return {1.0, 0.0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return {d1 / (d1 - d3), 0.0};
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return {0.0, 1.0};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return {0.0, d2 / (d2 - d6)};
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {1.0 - w, w};
  }
  const double denominator = 1.0 / (va + vb + vc);
  return {vb * denominator, vc * denominator};
}

Vec3 at_barycentric(const TriangleMesh& mesh, std::uint32_t t, double u, double v) {
  return (1.0 - u - v) * mesh.vertex(t, 0) + u * mesh.vertex(t, 1) + v * mesh.vertex(t, 2);
}

// The triangles around each triangle: those sharing a vertex with it (by position, so across an
// OBJ seam too), itself included.
std::vector<std::vector<std::uint32_t>> triangle_neighbours(const TriangleMesh& mesh) {
  const std::vector<std::uint32_t> ids = vertex_ids_by_position(mesh);
  const std::uint32_t id_count = ids.empty() ? 0 : *std::max_element(ids.begin(), ids.end()) + 1;
  std::vector<std::vector<std::uint32_t>> by_vertex(id_count);
  for (std::uint32_t t = 0; t < mesh.triangle_count(); ++t) {
    for (const std::uint32_t v : mesh.triangles[t]) by_vertex[ids[v]].push_back(t);
  }
  std::vector<std::vector<std::uint32_t>> neighbours(mesh.triangle_count());
  for (std::uint32_t t = 0; t < mesh.triangle_count(); ++t) {
    auto& list = neighbours[t];
    for (const std::uint32_t v : mesh.triangles[t]) {
      const auto& around = by_vertex[ids[v]];
      list.insert(list.end(), around.begin(), around.end());
    }
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  return neighbours;
}

// Where a point ends up on the surface: its triangle and barycentrics.
struct SurfaceSpot {
  std::uint32_t triangle = 0;
  double u = 0.0, v = 0.0;
};

// The nearest point of the mesh to `target`, found by walking from `start` to whichever triangle
// around the current one holds a nearer point, until none does (a push is shorter than the
// repulsion radius, so the walk is short: Turk's "moved along the surface").
SurfaceSpot walk_to_nearest(const TriangleMesh& mesh,
                            const std::vector<std::vector<std::uint32_t>>& neighbours,
                            std::uint32_t start, const Vec3& target) {
  SurfaceSpot best{start, 0.0, 0.0};
  std::tie(best.u, best.v) = closest_on_triangle(target, mesh.vertex(start, 0),
                                                 mesh.vertex(start, 1), mesh.vertex(start, 2));
  double best_distance = (at_barycentric(mesh, start, best.u, best.v) - target).squaredNorm();
  for (int step = 0; step < 256; ++step) {
    const std::uint32_t from = best.triangle;
    for (const std::uint32_t t : neighbours[from]) {
      if (t == from) continue;
      const auto [u, v] =
          closest_on_triangle(target, mesh.vertex(t, 0), mesh.vertex(t, 1), mesh.vertex(t, 2));
      const double distance = (at_barycentric(mesh, t, u, v) - target).squaredNorm();
      if (distance < best_distance) {
        best = {t, u, v};
        best_distance = distance;
      }
    }
    if (best.triangle == from) break;
  }
  return best;
}

// A point of triangle `from` pushed to `target` in its plane. Over a smooth surface the nearest
// point of the mesh is where it lands. Over a sharp edge (facets at more than 30 degrees, a
// box's) the nearest point is on the edge, and points pushed off a face would gather there; the
// part of the push beyond the edge is instead carried on over the face across it, folded down
// perpendicular to the edge (Bitterli §2.6.4: "projected onto their neighbouring polygon").
SurfaceSpot move_on_surface(const TriangleMesh& mesh,
                            const std::vector<std::vector<std::uint32_t>>& neighbours,
                            std::uint32_t from, const Vec3& target, double radius) {
  const SurfaceSpot spot = walk_to_nearest(mesh, neighbours, from, target);
  const Vec3 q = at_barycentric(mesh, spot.triangle, spot.u, spot.v);
  const double beyond = (target - q).norm();
  if (!(beyond > 1e-6 * radius)) return spot;
  // The face across the edge (or vertex) q lies on: of the triangles that touch q, the one
  // turned furthest from the face the point left.
  const Vec3 left = mesh.geometric_normal(from);
  double lowest = std::cos(std::numbers::pi / 6.0);
  std::uint32_t across = spot.triangle;
  for (const std::uint32_t t : neighbours[spot.triangle]) {
    const auto [u, v] =
        closest_on_triangle(q, mesh.vertex(t, 0), mesh.vertex(t, 1), mesh.vertex(t, 2));
    if ((at_barycentric(mesh, t, u, v) - q).norm() > 1e-9 * radius) continue;
    const double turn = left.dot(mesh.geometric_normal(t));
    if (turn < lowest) {
      lowest = turn;
      across = t;
    }
  }
  if (across == spot.triangle && lowest >= std::cos(std::numbers::pi / 6.0)) return spot;
  // Down the far face, perpendicular to the edge: -n_left in that face's plane.
  const Vec3 normal = mesh.geometric_normal(across);
  Vec3 down = -left + left.dot(normal) * normal;
  const double length = down.norm();
  if (!(length > 1e-9)) return spot;
  down /= length;
  return walk_to_nearest(mesh, neighbours, across, q + beyond * down);
}

// Points binned in cubic cells of side `cell` (at least the search radius), sorted by cell: the
// points within the search radius of any point lie in its cell and the 26 around it.
class PointGrid {
 public:
  PointGrid(const std::vector<Vec3>& points, const BoundingBox& box, double radius)
      : points_(points), lo_(box.lo) {
    // 21 bits per axis: the cells grow for a mesh far longer than its point spacing.
    const double extent = (box.hi - box.lo).maxCoeff();
    cell_ = std::max(radius, extent / static_cast<double>((1 << 20) - 2));
    entries_.reserve(points.size());
    for (std::uint32_t i = 0; i < points.size(); ++i)
      entries_.push_back({key(cell_of(points[i])), i});
    std::sort(entries_.begin(), entries_.end());
  }

  // f(j, d) for every other point j within `radius` (d its distance), in a fixed order.
  template <class F>
  void near(std::uint32_t i, double radius, F&& f) const {
    const std::array<std::int64_t, 3> c = cell_of(points_[i]);
    for (std::int64_t dz = -1; dz <= 1; ++dz)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::int64_t dx = -1; dx <= 1; ++dx) {
          const std::array<std::int64_t, 3> n = {c[0] + dx, c[1] + dy, c[2] + dz};
          if (n[0] < 0 || n[1] < 0 || n[2] < 0) continue;
          const std::uint64_t k = key(n);
          auto it = std::lower_bound(entries_.begin(), entries_.end(),
                                     std::pair<std::uint64_t, std::uint32_t>{k, 0});
          for (; it != entries_.end() && it->first == k; ++it) {
            if (it->second == i) continue;
            const double d = (points_[it->second] - points_[i]).norm();
            if (d < radius) f(it->second, d);
          }
        }
  }

 private:
  std::array<std::int64_t, 3> cell_of(const Vec3& p) const {
    const Vec3 s = (p - lo_) / cell_;
    return {static_cast<std::int64_t>(std::floor(s.x())),
            static_cast<std::int64_t>(std::floor(s.y())),
            static_cast<std::int64_t>(std::floor(s.z()))};
  }
  static std::uint64_t key(const std::array<std::int64_t, 3>& c) {
    return (static_cast<std::uint64_t>(c[2]) << 42) | (static_cast<std::uint64_t>(c[1]) << 21) |
           static_cast<std::uint64_t>(c[0]);
  }

  const std::vector<Vec3>& points_;
  Vec3 lo_;
  double cell_ = 1.0;
  std::vector<std::pair<std::uint64_t, std::uint32_t>> entries_;
};

// The box of the mesh, grown by `margin` on every side (points pushed slightly off the surface
// stay inside it).
BoundingBox grown(BoundingBox box, double margin) {
  box.lo.array() -= margin;
  box.hi.array() += margin;
  return box;
}

}  // namespace

PointCloud make_point_cloud(const TriangleMesh& mesh, const PointCloudOptions& options,
                            const WorkProgress& progress) {
  if (options.points < 1 || options.points > max_cloud_points) {
    throw InputError("points", fmt::format("got {}", options.points),
                     fmt::format("an integer in [1, {}]", max_cloud_points));
  }
  if (options.relaxation < 0 || options.relaxation > max_relaxation) {
    throw InputError("relaxation", fmt::format("got {}", options.relaxation),
                     fmt::format("an integer in [0, {}]", max_relaxation));
  }
  // The triangles' cumulative areas: the random start picks a triangle by area.
  std::vector<double> cumulative(mesh.triangle_count());
  double area = 0.0;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    area += mesh.area(t);
    cumulative[t] = area;
  }
  if (!(area > 0.0) || !std::isfinite(area)) {
    throw InputError("mesh", "the mesh has no area", "a closed mesh of triangles with area");
  }
  const auto n = static_cast<std::size_t>(options.points);
  PointCloud cloud;
  cloud.point_area = area / static_cast<double>(n);
  cloud.repulsion_radius = 2.0 * std::sqrt(cloud.point_area);
  std::vector<SurfaceSpot> spots(n);
  cloud.positions.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    PhotonRandom random(options.seed, i);
    const auto u = random.next4();
    const auto t = static_cast<std::uint32_t>(std::min<std::size_t>(
        static_cast<std::size_t>(
            std::upper_bound(cumulative.begin(), cumulative.end(), u[0] * area) -
            cumulative.begin()),
        mesh.triangle_count() - 1));
    // Uniform in the triangle: the square folded along its diagonal.
    double a = u[1], b = u[2];
    if (a + b > 1.0) {
      a = 1.0 - a;
      b = 1.0 - b;
    }
    spots[i] = {t, a, b};
    cloud.positions[i] = at_barycentric(mesh, t, a, b);
  }

  // Turk's repulsion (Turk 1992): every point moves by tau sum (r - d) (p - q) / d over its
  // neighbours q closer than r, in its tangent plane, all at once from the previous positions
  // (so the result does not depend on the order or the thread count). tau = 0.15 moves two
  // coincident points apart by 0.15 r = 0.28 of the lattice spacing per iteration; the push is
  // capped at r / 4 so that no point jumps past its neighbours.
  const auto neighbours = triangle_neighbours(mesh);
  const double r = cloud.repulsion_radius;
  const BoundingBox box = grown(mesh.bounds(), r);
  constexpr double tau = 0.15;
  std::vector<Vec3> next(n);
  std::vector<SurfaceSpot> next_spots(n);
  for (int iteration = 0; iteration < options.relaxation; ++iteration) {
    const PointGrid grid(cloud.positions, box, r);
#pragma omp parallel for schedule(static) \
    num_threads(options.threads > 0 ? options.threads : omp_get_max_threads())
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3& p = cloud.positions[i];
      Vec3 push = Vec3::Zero();
      grid.near(static_cast<std::uint32_t>(i), r, [&](std::uint32_t j, double d) {
        if (d > 1e-12 * r) push += tau * (r - d) / d * (p - cloud.positions[j]);
      });
      const Vec3 normal = mesh.geometric_normal(spots[i].triangle);
      push -= push.dot(normal) * normal;
      const double length = push.norm();
      if (length > 0.25 * r) push *= 0.25 * r / length;
      next_spots[i] = move_on_surface(mesh, neighbours, spots[i].triangle, p + push, r);
      next[i] = at_barycentric(mesh, next_spots[i].triangle, next_spots[i].u, next_spots[i].v);
    }
    std::swap(cloud.positions, next);
    std::swap(spots, next_spots);
    if (progress) {
      progress(static_cast<std::uint64_t>(iteration) + 1,
               static_cast<std::uint64_t>(options.relaxation));
    }
  }

  cloud.normals.resize(n);
  cloud.triangles.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const SurfaceSpot& s = spots[i];
    cloud.triangles[i] = s.triangle;
    const Vec3 normal = (1.0 - s.u - s.v) * mesh.corner_normal(s.triangle, 0) +
                        s.u * mesh.corner_normal(s.triangle, 1) +
                        s.v * mesh.corner_normal(s.triangle, 2);
    const double length = normal.norm();
    cloud.normals[i] = length > 0.0 ? Vec3(normal / length) : mesh.geometric_normal(s.triangle);
  }
  return cloud;
}

double nearest_neighbour_spread(const PointCloud& cloud) {
  const std::size_t n = cloud.size();
  if (n < 2) return 0.0;
  BoundingBox box{cloud.positions.front(), cloud.positions.front()};
  for (const Vec3& p : cloud.positions) {
    box.lo = box.lo.cwiseMin(p);
    box.hi = box.hi.cwiseMax(p);
  }
  const double r = cloud.repulsion_radius;
  const PointGrid grid(cloud.positions, grown(box, r), r);
  double sum = 0.0, sum2 = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    double nearest = std::numeric_limits<double>::infinity();
    grid.near(static_cast<std::uint32_t>(i), r,
              [&](std::uint32_t, double d) { nearest = std::min(nearest, d); });
    if (!std::isfinite(nearest)) {  // none within r (rare at the random start): look at all
      for (std::size_t j = 0; j < n; ++j) {
        if (j != i) nearest = std::min(nearest, (cloud.positions[j] - cloud.positions[i]).norm());
      }
    }
    sum += nearest;
    sum2 += nearest * nearest;
  }
  const double mean = sum / static_cast<double>(n);
  const double variance = std::max(sum2 / static_cast<double>(n) - mean * mean, 0.0);
  return std::sqrt(variance) / mean;
}

namespace {

// E_t at every point from light sources seen along directions: sources(p, emit) calls
// emit(direction to the source, its irradiance normal to that direction, distance to it) for each
// source seen from point p. E_t(p) = sum F_t(eta, cos theta) cos theta E_normal V (Bitterli eq.
// 2.14's cos(theta_i) L_i dw_i, times the entry F_t of eq. 2.16), V the visibility along the
// direction when `occlusion` (an Embree ray from just outside the facet; a source behind the
// facet itself is blocked by it).
template <class Sources>
std::vector<double> irradiance_from(const TriangleMesh& mesh, const PointCloud& cloud, double eta,
                                    bool occlusion, int threads, const Sources& sources) {
  std::optional<MeshRayTracer> tracer;
  if (occlusion) tracer.emplace(mesh);
  const double eps = occlusion ? tracer->epsilon() : 0.0;
  const auto n = static_cast<std::ptrdiff_t>(cloud.size());
  std::vector<double> irradiance(cloud.size(), 0.0);
#pragma omp parallel for schedule(dynamic, 256) \
    num_threads(threads > 0 ? threads : omp_get_max_threads())
  for (std::ptrdiff_t i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const Vec3& p = cloud.positions[k];
    const Vec3& normal = cloud.normals[k];
    const Vec3 facet = mesh.geometric_normal(cloud.triangles[k]);
    double sum = 0.0;
    sources(p, [&](const Vec3& direction, double normal_irradiance, double distance) {
      const double cos_in = normal.dot(direction);
      if (!(cos_in > 0.0)) return;
      if (occlusion) {
        if (!(facet.dot(direction) > 0.0)) return;
        if (tracer->occluded(p + eps * facet, direction, 0.0, distance - 2.0 * eps)) return;
      }
      sum += fresnel_dielectric_transmittance(cos_in, eta) * cos_in * normal_irradiance;
    });
    irradiance[k] = sum;
  }
  return irradiance;
}

}  // namespace

std::vector<double> point_irradiance(const RenderScene& scene, const PointCloud& cloud,
                                     bool occlusion, int threads) {
  const std::vector<LightPoint> lights =
      light_points(scene.light, scene.light_samples, scene.mesh.bounds().center());
  // A point source of intensity I at distance d: irradiance I / d^2 normal to the direction.
  return irradiance_from(scene.mesh, cloud, scene.eta, occlusion, threads,
                         [&](const Vec3& p, const auto& emit) {
                           for (const LightPoint& light : lights) {
                             const Vec3 to_light = light.position - p;
                             const double d2 = to_light.squaredNorm();
                             const double d = std::sqrt(d2);
                             emit(Vec3(to_light / d), light.intensity / d2, d);
                           }
                         });
}

std::vector<double> directional_irradiance(const TriangleMesh& mesh, const PointCloud& cloud,
                                           const DirectionalLight& light, double eta,
                                           bool occlusion, int threads) {
  const double norm = light.to_light.norm();
  if (!(norm > 0.0) || !std::isfinite(norm)) {
    throw InputError("light.direction", "zero or not finite", "a direction of length > 0");
  }
  const Vec3 to_light = light.to_light / norm;
  return irradiance_from(mesh, cloud, eta, occlusion, threads, [&](const Vec3&, const auto& emit) {
    emit(to_light, light.irradiance, std::numeric_limits<double>::infinity());
  });
}

}  // namespace scatterlab
