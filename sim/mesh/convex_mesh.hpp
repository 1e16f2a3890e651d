#pragma once
// Whether a closed triangle mesh bounds a convex solid: then light that leaves it can never meet
// it again, and the transport in it (mesh_boundary.hpp) spares the ray query that looks for a
// re-entry.

#include <vector>

#include "scatterlab/core/triangle_mesh.hpp"

namespace scatterlab {

// For a closed, consistently oriented mesh (render_scene.hpp, require_closed_mesh): true when it
// is one piece and convex at every edge (the far corner of each neighbouring triangle on or
// below the triangle's plane, to 1e-9 of the mesh's size). A closed connected surface that is
// locally convex everywhere bounds a convex solid (Tietze's theorem), so the test is exact.
bool bounds_convex_solid(const TriangleMesh& mesh);

// The plane of a face, n . (p - about) = offset with n the outward unit normal.
struct FacePlane {
  Vec3 normal;
  double offset = 0.0;
};

// The distinct planes of the facets of a mesh that bounds a convex solid, about the point
// `about`: facets whose unit normals agree to 1e-12 and whose offsets agree to 1e-12 of the mesh's
// size share one, the outermost. Empty when there are more than `most` (a tessellated curve).
std::vector<FacePlane> face_planes(const TriangleMesh& mesh, const Vec3& about, std::size_t most);

}  // namespace scatterlab
