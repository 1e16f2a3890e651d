#pragma once
// A closed or open triangle mesh bounding a medium: positions, optional per-vertex shading
// normals (interpolated across each triangle, Phong style) and vertex indices. Pure geometry, in
// core so that any module (a mesh random-walk kernel, the refractive solver, a renderer, an OBJ
// reader) can share it without depending on one another.
//
// Conventions (Walter et al. 2009, §3.1): triangles are counter-clockwise seen from outside, so
// the geometric normal (p1 - p0) x (p2 - p0) points out of the medium; shading normals point out
// of the medium too.

#include <array>
#include <cstdint>
#include <vector>

#include "scatterlab/core/frame.hpp"

namespace scatterlab {

// An axis-aligned box.
struct BoundingBox {
  Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();

  Vec3 center() const { return 0.5 * (lo + hi); }
  double diagonal() const { return (hi - lo).norm(); }
};

struct TriangleMesh {
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;  // empty (flat facets), or one unit normal per position
  std::vector<std::array<std::uint32_t, 3>> triangles;

  bool has_shading_normals() const { return !normals.empty(); }
  std::size_t triangle_count() const { return triangles.size(); }

  const Vec3& vertex(std::size_t triangle, int corner) const {
    return positions[triangles[triangle][static_cast<std::size_t>(corner)]];
  }
  // Shading normal at a corner: the stored vertex normal, or the geometric normal when flat.
  Vec3 corner_normal(std::size_t triangle, int corner) const;
  // Unit outward geometric normal (zero vector for a degenerate triangle).
  Vec3 geometric_normal(std::size_t triangle) const;
  double area(std::size_t triangle) const;
  // The box of the positions (a zero box for an empty mesh).
  BoundingBox bounds() const;

  // Throws InputError naming the field: indices out of range, non-finite positions, normals
  // neither empty nor one per position, or normals that are not unit length.
  void validate() const;
};

// One id per distinct position, for every vertex: vertices at the same place (an OBJ seam where
// normals split) share it, so that edges can be matched across the seam.
std::vector<std::uint32_t> vertex_ids_by_position(const TriangleMesh& mesh);

// For every triangle, the triangle across each of its edges (corner k to corner k + 1): the one
// that holds the same edge reversed, its corners matched by `id` (vertex_ids_by_position), or
// no_triangle where none does (an open edge).
inline constexpr std::uint32_t no_triangle = 0xffffffffU;
std::vector<std::array<std::uint32_t, 3>> triangles_across_edges(
    const TriangleMesh& mesh, const std::vector<std::uint32_t>& id);

// Area-weighted average of the facet normals around each vertex, normalised: smooth shading
// normals for a mesh that has none.
std::vector<Vec3> area_weighted_vertex_normals(const TriangleMesh& mesh);

// Adds `part`, moved by `shift`, to `mesh` as more triangles of the same mesh: one mesh of
// several closed parts. Shading normals are kept when both have them (or `mesh` is empty);
// std::invalid_argument when only one of two non-empty meshes has them.
void append_mesh(TriangleMesh& mesh, const TriangleMesh& part, const Vec3& shift);

}  // namespace scatterlab
