#pragma once
// What a triangle mesh must be to bound a medium: closed and consistently oriented, enclosing a
// positive volume, and a surface that does not pass through itself, so that inside and outside
// by crossing parity are right. Each check throws InputError("mesh", ...) naming what is wrong.

#include "scatterlab/core/triangle_mesh.hpp"

namespace scatterlab {

// Throws naming the edge when the mesh is open or non-manifold.
void require_closed_mesh(const TriangleMesh& mesh);

// Throws naming the triangle when one has zero area (relative to the mesh's extent), and when the
// mesh encloses no positive volume (flat, or inside out).
void require_enclosed_volume(const TriangleMesh& mesh);

// Throws naming two triangles when an edge of one passes through the other: overlapping closed
// parts, whose inside by crossing parity would be wrong. For a closed mesh (require_closed_mesh).
void require_no_self_intersection(const TriangleMesh& mesh);

}  // namespace scatterlab
