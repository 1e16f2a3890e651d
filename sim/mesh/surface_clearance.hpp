#pragma once
// How far a point inside a mesh is at least from its surface: a lower bound read from a grid
// over the mesh's box, so that the random walk (mesh_boundary.hpp) skips the ray query of a
// flight too short to reach the surface, as most flights deep inside a large object are, and
// the lane walk decides such plain events for all its lanes at once
// (transport/object_boundary.hpp).
//
// A triangle may meet the cells of its box whose centre lies within half the cell's extent along
// its normal, h/2 (|n_x| + |n_y| + |n_z|), of its plane (h the cell's side): those are marked, with
// a margin of a millionth of a cell, so every point of the surface lies in a marked cell and no
// triangle comes within the margin of a cell left unmarked. Every other cell holds its
// Chebyshev distance k (in cells) to the nearest marked one, by a breadth-first sweep; points of
// two cells k apart along some axis are at least (k - 1) h apart, so no surface point is within
// max((k - 1) h, margin) of any point of the cell.
//
// An unmarked cell holds no surface point, and lies wholly inside the mesh or wholly outside
// it, as do the cells joined to it face to face through unmarked cells: each such region is
// inside or outside as the parity of a ray from one of its points says. Cells outside, and
// marked cells, hold 0.

#include <cstdint>
#include <vector>

#include "scatterlab/core/triangle_mesh.hpp"
#include "scatterlab/mesh/mesh_ray_tracer.hpp"
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
  std::vector<std::uint8_t> code_;  // min(k, 255) inside; 0 elsewhere
  float clearance_of_[256] = {};    // the bound of each k, a millionth under, rounded down
  InteriorClearance grid_;
};

}  // namespace scatterlab
