#include "convex_crossing.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

namespace scatterlab {

namespace {

// The octahedral map of directions onto the square [-1, 1]^2 (Cigolle et al. 2014, "A Survey of
// Efficient Representations for Independent Unit Vectors", JCGT 3(2), §3.1): u / |u|_1 for the
// upper half, the lower half folded out over the square's corners. Selects by a mask, not
// branches (which the compiler makes of a conditional here): the half is as good as random,
// and a mispredicted branch costs more than the rest of the lookup.
std::array<double, 2> octahedral(const Vec3& u) {
  const double norm = std::abs(u.x()) + std::abs(u.y()) + std::abs(u.z());
  const double scale = 1.0 / std::max(norm, 1e-300);  // u = 0: any cell will do
  const double x = u.x() * scale, y = u.y() * scale;
  const double folded_x = std::copysign(1.0 - std::abs(y), x);
  const double folded_y = std::copysign(1.0 - std::abs(x), y);
  const std::uint64_t lower = std::uint64_t{0} - static_cast<std::uint64_t>(u.z() < 0.0);
  const auto select = [lower](double upper_value, double lower_value) {
    return std::bit_cast<double>((std::bit_cast<std::uint64_t>(upper_value) & ~lower) |
                                 (std::bit_cast<std::uint64_t>(lower_value) & lower));
  };
  return {select(x, folded_x), select(y, folded_y)};
}

// The direction of the point (s, t) of the octahedral map, not normalized.
Vec3 from_octahedral(double s, double t) {
  const double z = 1.0 - std::abs(s) - std::abs(t);
  if (z >= 0.0) return {s, t, z};
  return {std::copysign(1.0 - std::abs(t), s), std::copysign(1.0 - std::abs(s), t), z};
}

}  // namespace

ConvexCrossing::ConvexCrossing(const TriangleMesh& mesh, const MeshRayTracer& tracer) {
  // Corners by position, so that facets across an OBJ seam share their edge's corners.
  const std::vector<std::uint32_t> id = vertex_ids_by_position(mesh);
  const std::size_t n = mesh.triangle_count();
  facets_.resize(n);
  const auto across = triangles_across_edges(mesh, id);
  planes_.resize(n);
  centroid_ = Vec3::Zero();
  for (std::size_t t = 0; t < n; ++t) {
    centroid_ += (mesh.vertex(t, 0) + mesh.vertex(t, 1) + mesh.vertex(t, 2)) / 3.0;
    Plane& plane = planes_[t];
    plane.normal = mesh.geometric_normal(t);
    plane.offset = plane.normal.dot(mesh.vertex(t, 0));
  }
  centroid_ /= static_cast<double>(std::max<std::size_t>(n, 1));
  // Each edge once, from its lower corner to its higher, about the centroid.
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> edge_of;
  for (std::size_t t = 0; t < n; ++t) {
    Facet& f = facets_[t];
    for (int k = 0; k < 3; ++k) {
      const int next = (k + 1) % 3;
      const std::uint32_t from = id[mesh.triangles[t][k]], to = id[mesh.triangles[t][next]];
      const bool rising = from < to;
      if (rising) f.rising |= 1U << k;
      f.across[k] = across[t][static_cast<std::size_t>(k)];
      const auto [it, added] = edge_of.try_emplace({std::min(from, to), std::max(from, to)},
                                                   static_cast<std::uint32_t>(edges_.size()));
      if (added) {
        const Vec3 a = mesh.vertex(t, rising ? k : next) - centroid_;
        const Vec3 b = mesh.vertex(t, rising ? next : k) - centroid_;
        edges_.push_back({a.cross(b), b - a});
      }
      f.edge[k] = it->second;
    }
  }
  radius_ = 0.0;
  for (const Vec3& v : mesh.positions) radius_ = std::max(radius_, (v - centroid_).norm());
  inner_radius_ = radius_;
  for (const Plane& plane : planes_) {
    inner_radius_ = std::min(inner_radius_, plane.offset - plane.normal.dot(centroid_));
  }

  // About four cells a facet, so that where facets are small (a sphere's poles) the walk
  // starts near: 4 n cells, 2 MiB at most.
  map_cells_ =
      std::clamp(static_cast<int>(std::ceil(2.0 * std::sqrt(static_cast<double>(n)))), 1, 724);
  const int r = map_cells_;
  start_.assign(static_cast<std::size_t>(r) * r, 0);
  for (int i = 0; i < r; ++i) {
    for (int j = 0; j < r; ++j) {
      const Vec3 u = from_octahedral(2.0 * (i + 0.5) / r - 1.0, 2.0 * (j + 0.5) / r - 1.0);
      MeshHit hit;
      if (tracer.intersect(centroid_, u.normalized(), 0.0, std::numeric_limits<double>::infinity(),
                           hit)) {
        start_[static_cast<std::size_t>(i) * r + j] = hit.triangle;
      }
    }
  }
  // A walk crosses about one facet per cell of the table it is off by; from a poor start it
  // may cross the mesh, some 2 sqrt(n) facets.
  max_steps_ = 64 + 4 * static_cast<int>(std::sqrt(static_cast<double>(n)));
}

std::uint32_t ConvexCrossing::start(const Vec3& near) const {
  const std::array<double, 2> st = octahedral(near - centroid_);
  const int r = map_cells_;
  // |s|, |t| <= 1, a rounding over at most: the cell is in [0, r].
  const auto cell = [r](double s) {
    return std::min(static_cast<int>((s + 1.0) * 0.5 * r), r - 1);
  };
  return start_[static_cast<std::size_t>(cell(st[0])) * r + cell(st[1])];
}

ConvexCrossing::Walk ConvexCrossing::leave(const Vec3& origin, const Vec3& direction,
                                           MeshCrossing& at, double& cos_incidence) const {
  // Start where the ray leaves the ball about the centroid that holds the object:
  // |origin - centroid + t direction| = radius.
  const Vec3 from_centroid = origin - centroid_;
  const double along = from_centroid.dot(direction);
  const double t =
      -along +
      std::sqrt(std::max(along * along - from_centroid.squaredNorm() + radius_ * radius_, 0.0));
  return walk(1.0, origin, direction, start(origin + t * direction), at, cos_incidence);
}

ConvexCrossing::Walk ConvexCrossing::enter(const Vec3& origin, const Vec3& direction,
                                           MeshCrossing& at, double& cos_incidence) const {
  // The object lies within `radius_` of its centroid: a line that passes farther, or a ray
  // from outside that ball going away from it, misses.
  const Vec3 to_centroid = centroid_ - origin;
  const double along = to_centroid.dot(direction);
  const Vec3 closest = origin + along * direction;  // the line's point nearest the centroid
  const double squared_miss = (closest - centroid_).squaredNorm();
  if (squared_miss > radius_ * radius_ ||
      (along <= 0.0 && to_centroid.squaredNorm() > radius_ * radius_)) {
    return Walk::misses;
  }
  // Start where the line comes within the ball, on the side the light comes from.
  std::uint32_t from = start(closest - std::sqrt(radius_ * radius_ - squared_miss) * direction);
  // The walk in the shadow goes over facets facing the light alone: from a start that faces
  // away (an elongated object), first to the neighbour that faces the light most.
  for (int step = 0; !(planes_[from].normal.dot(direction) < 0.0); ++step) {
    if (step == max_steps_) return Walk::gave_up;
    const Facet& f = facets_[from];
    from = f.across[0];
    for (int k = 1; k < 3; ++k) {
      if (planes_[f.across[k]].normal.dot(direction) < planes_[from].normal.dot(direction)) {
        from = f.across[k];
      }
    }
  }
  return walk(-1.0, origin, direction, from, at, cos_incidence);
}

ConvexCrossing::Walk ConvexCrossing::walk(double inward, const Vec3& origin, const Vec3& direction,
                                          std::uint32_t from, MeshCrossing& at,
                                          double& cos_incidence) const {
  constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();
  std::uint32_t facet = from, came_from = none;
  const Vec3 moment = (origin - centroid_).cross(direction);  // the ray's, about the centroid
  for (int step = 0; step < max_steps_; ++step) {
    const Facet& f = facets_[facet];
    int beyond = -1;
    for (int i = 0; i < 3; ++i) {
      const int k = (i + step) % 3;
      if (f.across[k] == came_from) continue;  // the ray passes on this side of the edge it came by
      const Edge& e = edges_[f.edge[k]];
      const double product = e.moment.dot(direction) + e.along.dot(moment);
      const int rising = static_cast<int>((f.rising >> k) & 1U);
      if (inward * (2 * rising - 1) * product < 0.0) {
        beyond = k;
        break;
      }
    }
    if (beyond < 0) {
      const Plane& plane = planes_[facet];
      const double cos_normal = plane.normal.dot(direction);
      if (!(inward * cos_normal > 0.0)) return Walk::gave_up;  // grazing the facet
      const double distance = (plane.offset - plane.normal.dot(origin)) / cos_normal;
      // From outside, a line that enters behind its origin has passed the object.
      if (inward < 0.0 && !(distance > 0.0)) return Walk::misses;
      at.triangle = facet;
      at.distance = std::max(distance, 0.0);  // a point on the surface may round outside
      at.point = origin + at.distance * direction;
      at.normal = plane.normal;
      cos_incidence = inward * cos_normal;
      return Walk::crosses;
    }
    came_from = facet;
    facet = f.across[beyond];
    // Entering, a step off the facets that face the light crosses the rim of the shadow.
    if (inward < 0.0 && !(planes_[facet].normal.dot(direction) < 0.0)) return Walk::misses;
  }
  return Walk::gave_up;
}

}  // namespace scatterlab
