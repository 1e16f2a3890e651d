#pragma once
// How far a point inside a mesh is at least from its surface: a lower bound read from a grid
// over the mesh's box, so that the random walk (mesh_boundary.hpp) skips the ray query of a
// flight too short to reach the surface, as most flights deep inside a large object are, and
// the lane walk decides such plain events for all its lanes at once
// (transport/object_boundary.hpp).
//
// Points spread over every triangle, none farther than h / 2 from any point of it (h the cell's
// side), mark their cells; every other cell holds its Chebyshev distance k (in cells) to the
// nearest marked one, by a breadth-first sweep. Points of two cells k apart along some axis are
// at least (k - 1) h apart, and every surface point is within h / 2 of a point in a marked cell,
// so no surface point is within (k - 3/2) h of any point of the cell.
//
// A cell with k >= 2 therefore holds no surface point, and lies wholly inside the mesh or wholly
// outside it, as do the cells joined to it face to face through such cells: each such region
// is inside or outside as the parity of a ray from one of its points says. Cells outside, and
// those the surface may cross, hold 0.

#include <vector>

#include "scatterlab/core/triangle_mesh.hpp"
#include "scatterlab/render/mesh_ray_tracer.hpp"
#include "scatterlab/transport/object_boundary.hpp"

namespace scatterlab {

class SurfaceClearance {
 public:
  // `tracer` is over `mesh`, closed; `cells` along the box's longest side.
  SurfaceClearance(const TriangleMesh& mesh, const MeshRayTracer& tracer, int cells = 64);
  // The grid points into the object's own cells.
  SurfaceClearance(const SurfaceClearance&) = delete;
  SurfaceClearance& operator=(const SurfaceClearance&) = delete;

  // A distance within which no point of the surface lies, for a point inside the mesh; 0 near
  // the surface and outside the mesh.
  double at(const Vec3& point) const { return grid_.at(point); }

  // The grid, for the lane walk; it reads this object's cells.
  const InteriorClearance& interior() const { return grid_; }

 private:
  std::vector<double> clearance_;  // (k - 3/2) h a millionth under, inside; 0 elsewhere
  InteriorClearance grid_;
};

}  // namespace scatterlab
