#pragma once
// Whether a closed triangle mesh bounds a convex solid: then light that leaves it can never meet
// it again, and the transport in it (mesh_boundary.hpp) spares the ray query that looks for a
// re-entry.

#include "scatterlab/core/triangle_mesh.hpp"

namespace scatterlab {

// For a closed, consistently oriented mesh (render_scene.hpp, require_closed_mesh): true when it
// is one piece and convex at every edge (the far corner of each neighbouring triangle on or
// below the triangle's plane, to 1e-9 of the mesh's size). A closed connected surface that is
// locally convex everywhere bounds a convex solid (Tietze's theorem), so the test is exact.
bool bounds_convex_solid(const TriangleMesh& mesh);

}  // namespace scatterlab
