#pragma once
// Ray-mesh queries with Embree 3 (one static scene over one TriangleMesh). Embree works in single
// precision; hit points are recomputed in double from the triangle and Embree's barycentrics, and
// rays start a small offset off the surface they leave.

#include <cstdint>
#include <limits>
#include <memory>

#include "scatterlab/core/triangle_mesh.hpp"

namespace scatterlab {

struct MeshHit {
  std::uint32_t triangle = 0;
  double distance = 0.0;              // along the (unit) direction, from the ray's origin
  double bary_a = 0.0, bary_b = 0.0;  // point = (1 - a - b) p0 + a p1 + b p2
};

// Where a ray meets a closed mesh: the point, in double, and the facet's outward unit normal.
struct MeshCrossing {
  Vec3 point;
  Vec3 normal;
  std::uint32_t triangle = 0;
  double distance = 0.0;  // along the (unit) direction, from the ray's origin
};

class MeshRayTracer {
 public:
  // Throws std::runtime_error when Embree cannot start.
  explicit MeshRayTracer(const TriangleMesh& mesh);
  ~MeshRayTracer();
  MeshRayTracer(const MeshRayTracer&) = delete;
  MeshRayTracer& operator=(const MeshRayTracer&) = delete;

  // Closest hit with distance in (t_near, t_far); false on a miss. Thread-safe.
  bool intersect(const Vec3& origin, const Vec3& direction, double t_near, double t_far,
                 MeshHit& hit) const;
  // Whether anything lies in (t_near, t_far). Thread-safe.
  bool occluded(const Vec3& origin, const Vec3& direction, double t_near, double t_far) const;

  // Crossings of the ray (t_near, inf) with the mesh: odd means the origin is inside a closed
  // mesh.
  int count_crossings(const Vec3& origin, const Vec3& direction) const;

  // An offset that clears single-precision self-intersection: 1e-5 of the mesh's size.
  double epsilon() const { return epsilon_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  double epsilon_ = 0.0;
};

}  // namespace scatterlab
