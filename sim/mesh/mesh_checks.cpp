#include "scatterlab/mesh/mesh_checks.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "scatterlab/core/error.hpp"
#include "scatterlab/mesh/mesh_ray_tracer.hpp"

namespace scatterlab {

void require_closed_mesh(const TriangleMesh& mesh) {
  // Vertices are matched by position, so that OBJ seams where normals split still close.
  const std::vector<std::uint32_t> id = vertex_ids_by_position(mesh);
  // Each directed edge once, and its reverse once: closed, manifold, consistently oriented.
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  for (const auto& t : mesh.triangles) {
    for (int c = 0; c < 3; ++c) {
      ++directed[{id[t[static_cast<std::size_t>(c)]],
                  id[t[static_cast<std::size_t>((c + 1) % 3)]]}];
    }
  }
  for (const auto& [edge, count] : directed) {
    const auto reverse = directed.find({edge.second, edge.first});
    const int opposite = reverse == directed.end() ? 0 : reverse->second;
    if (count != 1 || opposite != 1) {
      throw InputError(
          "mesh",
          fmt::format("not a closed, consistently oriented mesh: an edge is used {} time(s) in "
                      "one direction and {} in the other",
                      count, opposite),
          "a closed (watertight), manifold triangle mesh, counter-clockwise seen from outside");
    }
  }
}

namespace {

// Whether the segment [p, q] crosses the triangle uvw properly: its ends on opposite sides of the
// triangle's plane, each farther than `tolerance`, and the crossing point inside the triangle. An
// edge that lies in the plane, or ends in it (at a corner it shares), does not cross.
bool crosses(const Vec3& p, const Vec3& q, const Vec3& u, const Vec3& v, const Vec3& w,
             double tolerance) {
  const Vec3 normal = (v - u).cross(w - u).normalized();
  const double from = normal.dot(p - u), to = normal.dot(q - u);
  if (!((from > tolerance && to < -tolerance) || (from < -tolerance && to > tolerance))) {
    return false;
  }
  const Vec3 x = p + (q - p) * (from / (from - to));
  return normal.dot((v - u).cross(x - u)) > 0.0 && normal.dot((w - v).cross(x - v)) > 0.0 &&
         normal.dot((u - w).cross(x - w)) > 0.0;
}

}  // namespace

void require_no_self_intersection(const TriangleMesh& mesh) {
  // Two surfaces cross where an edge of one passes through a triangle of the other, so each edge
  // is traced from end to end: Embree finds the triangles near it (in single precision, where an
  // edge grazes its neighbours), and each is confirmed in double (crosses). Overlaps confined to
  // one plane, with no edge through a face, are not seen.
  const std::vector<std::uint32_t> id = vertex_ids_by_position(mesh);
  const MeshRayTracer tracer(mesh);
  const double margin = tracer.epsilon();
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const auto& corners = mesh.triangles[t];
    for (std::size_t c = 0; c < 3; ++c) {
      const std::uint32_t a = corners[c], b = corners[(c + 1) % 3];
      if (id[a] > id[b]) continue;  // each edge once: a closed mesh holds it in both directions
      const Vec3 from = mesh.positions[a], to = mesh.positions[b];
      const double length = (to - from).norm();
      MeshHit hit;
      for (double near = 0.0; tracer.intersect(from, (to - from) / length, near, length, hit);
           near = std::max(near + margin, hit.distance)) {
        const std::size_t other = hit.triangle;
        if (crosses(from, to, mesh.vertex(other, 0), mesh.vertex(other, 1), mesh.vertex(other, 2),
                    margin)) {
          throw InputError("mesh",
                           fmt::format("intersects itself: an edge of triangle {} passes through "
                                       "triangle {}",
                                       t, other),
                           "a surface that does not pass through itself (closed parts that do "
                           "not overlap)");
        }
      }
    }
  }
}

void require_enclosed_volume(const TriangleMesh& mesh) {
  // The mesh's extent sets the scale below which an area or a volume is round-off, not geometry.
  Vec3 lowest = mesh.positions.front(), highest = lowest;
  for (const Vec3& p : mesh.positions) {
    lowest = lowest.cwiseMin(p);
    highest = highest.cwiseMax(p);
  }
  const double extent = (highest - lowest).maxCoeff();
  constexpr double relative = 1e-12;
  // Divergence theorem: V = (1/6) sum over triangles of a . (b x c), exact for a closed mesh.
  double six_volume = 0.0;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const Vec3 a = mesh.vertex(t, 0), b = mesh.vertex(t, 1), c = mesh.vertex(t, 2);
    if (!((b - a).cross(c - a).norm() > relative * extent * extent)) {
      throw InputError("mesh", fmt::format("triangle {} has zero area", t),
                       "triangles whose three corners are distinct and not collinear");
    }
    six_volume += a.dot(b.cross(c));
  }
  if (!(six_volume > relative * extent * extent * extent)) {
    throw InputError(
        "mesh", fmt::format("encloses a volume of {:g} (extent {:g})", six_volume / 6.0, extent),
        "a mesh enclosing a positive volume, counter-clockwise seen from outside (an inside-out "
        "mesh has a negative one)");
  }
}


}  // namespace scatterlab
