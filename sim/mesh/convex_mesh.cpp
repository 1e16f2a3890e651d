#include "convex_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <utility>
#include <vector>

namespace scatterlab {

bool bounds_convex_solid(const TriangleMesh& mesh) {
  if (mesh.triangle_count() == 0) return false;
  // Vertices by position, so that OBJ seams where normals split still join (as
  // require_closed_mesh matches them).
  const auto across = triangles_across_edges(mesh, vertex_ids_by_position(mesh));
  // Pieces by union-find over triangles that share an edge.
  std::vector<std::size_t> parent(mesh.triangle_count());
  std::iota(parent.begin(), parent.end(), std::size_t{0});
  const auto root = [&parent](std::size_t t) {
    while (parent[t] != t) t = parent[t] = parent[parent[t]];
    return t;
  };
  const double tolerance = 1e-9 * mesh.bounds().diagonal();
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const Vec3 normal = mesh.geometric_normal(t);
    const Vec3& origin = mesh.vertex(t, 0);
    for (const std::uint32_t u : across[t]) {
      if (u == no_triangle) return false;  // open: not a solid
      for (int k = 0; k < 3; ++k) {
        if (normal.dot(mesh.vertex(u, k) - origin) > tolerance) return false;
      }
      parent[root(t)] = root(u);
    }
  }
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    if (root(t) != root(0)) return false;
  }
  return true;
}

std::vector<FacePlane> face_planes(const TriangleMesh& mesh, const Vec3& about, std::size_t most) {
  const double size = mesh.bounds().diagonal();
  std::vector<FacePlane> planes;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const Vec3 normal = mesh.geometric_normal(t);
    const double offset = normal.dot(mesh.vertex(t, 0) - about);
    const auto same = std::find_if(planes.begin(), planes.end(), [&](const FacePlane& plane) {
      return (plane.normal - normal).cwiseAbs().maxCoeff() <= 1e-12 &&
             std::abs(plane.offset - offset) <= 1e-12 * size;
    });
    if (same != planes.end()) {
      same->offset = std::max(same->offset, offset);
      continue;
    }
    if (planes.size() == most) return {};
    planes.push_back({normal, offset});
  }
  return planes;
}

}  // namespace scatterlab
