#pragma once
// How far a point inside a mesh is at least from its surface: a lower bound read from a grid
// over the mesh's box, so that the random walk (mesh_boundary.hpp) skips the ray query of a
// flight too short to reach the surface, as most flights deep inside a large object are.
//
// Points spread over every triangle, none farther than h / 2 from any point of it (h the cell's
// side), mark their cells; every other cell holds its Chebyshev distance k (in cells) to the
// nearest marked one, by a breadth-first sweep. Points of two cells k apart along some axis are
// at least (k - 1) h apart, and every surface point is within h / 2 of a point in a marked cell,
// so no surface point is within (k - 3/2) h of any point of the cell. Held in single precision,
// rounded down.

#include <cstdint>
#include <vector>

#include "scatterlab/core/frame.hpp"
#include "scatterlab/core/triangle_mesh.hpp"

namespace scatterlab {

class SurfaceClearance {
 public:
  // `cells`: along the box's longest side.
  explicit SurfaceClearance(const TriangleMesh& mesh, int cells = 64);

  // A distance within which no point of the surface lies; 0 near it, and outside the box.
  double at(const Vec3& point) const {
    const Vec3 cell = (point - lo_) * inverse_side_;
    if (!(cell.minCoeff() >= 0.0) || !(cell.x() < n_[0] && cell.y() < n_[1] && cell.z() < n_[2])) {
      return 0.0;
    }
    const auto index = static_cast<std::size_t>(
        (static_cast<int>(cell.z()) * n_[1] + static_cast<int>(cell.y())) * n_[0] +
        static_cast<int>(cell.x()));
    return clearance_of_[steps_[index]];
  }

 private:
  Vec3 lo_;
  double inverse_side_ = 0.0;
  int n_[3] = {1, 1, 1};
  std::vector<std::uint8_t> steps_;  // k per cell
  double clearance_of_[256] = {};    // (k - 3/2) h, at least 0, a millionth under
};

}  // namespace scatterlab
