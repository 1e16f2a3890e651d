#pragma once
// A convex object whose surface another module traces (a closed triangle mesh:
// mesh/mesh_boundary.hpp), as the lane walk (lane_walk.hpp) runs it.
//
// The lanes decide the plain event for all lanes at once: a flight from a point inside a convex
// object to a point inside it stays inside, and InteriorClearance says which points lie wholly
// inside. A flight that may meet the surface, and the launch of each photon by the object's
// light, go to the object's own code through a function pointer: the one indirect call is on
// that rare path, beside a search of the surface that costs many times more, and the plain
// event has none; nor does a flight the lanes found inside, which the object does not test
// again. (In an object that is not convex, only a flight shorter than a clearance
// could pass, the lanes take most events one at a time, and they run no faster than the
// one-photon walk, which the engine gives such objects.)

#include <array>
#include <cstddef>
#include <cstdint>

#include "scatterlab/core/frame.hpp"
#include "scatterlab/core/random.hpp"
#include "scatterlab/tally/surface_exit.hpp"

namespace scatterlab {

// A grid over an object's box, one byte a cell (small enough to stay in cache). Each cell's
// byte is the index of its clearance c in a table of 256: 0 where the surface may pass
// through the cell, or where the cell lies outside the object; otherwise the cell is wholly
// inside, and no point of the surface lies within c of any point of it. So a flight from a
// point p inside stays inside when it is shorter than c(p) (the ball of radius c(p) about p holds
// no point of the surface), and in a convex object when it ends in a cell with c > 0 (both its
// ends are inside), or in its core: a ball wholly inside it, which passes in one comparison the
// flights that end deep inside a round object and spares the grid's read.
//
// A convex polyhedron of few faces (a box, a prism) is the intersection of its faces' half-spaces,
// and a point lies inside it exactly when it lies below every face's plane: a test that decides
// every flight, near the surface too, where the grid's cells that the surface passes through
// (a layer a cell deep, 3 mfp in a block of 200) would send each flight to a search of the
// surface. The planes are held a margin inside, so that no rounding passes a point outside.
struct InteriorClearance {
  Vec3 lo = Vec3::Zero();     // the grid's corner
  double inverse_side = 0.0;  // 1 / the cells' side
  int cells[3] = {0, 0, 0};   // along x, y and z
  // Per cell, x fastest, then y.
  const std::uint8_t* code = nullptr;
  const float* clearance_of = nullptr;  // c of each code; clearance_of[0] = 0
  Vec3 core_centre = Vec3::Zero();
  double core_radius2 = -1.0;  // the core's squared radius; none when negative
  // The faces' planes n . (p - core_centre) < offset, when there are at most max_faces; then
  // they alone decide, and the core and the grid are not read.
  static constexpr int max_faces = 8;
  int faces = 0;
  std::array<double, max_faces> face_x{}, face_y{}, face_z{}, face_offset{};

  // c of the cell that holds `point`; 0 outside the grid. The lane walk reads it for the lanes
  // outside the core.
  double at(const Vec3& point) const {
    const double x = (point.x() - lo.x()) * inverse_side, y = (point.y() - lo.y()) * inverse_side,
                 z = (point.z() - lo.z()) * inverse_side;
    if (!(x >= 0.0 && y >= 0.0 && z >= 0.0 && x < cells[0] && y < cells[1] && z < cells[2])) {
      return 0.0;
    }
    const auto index = (static_cast<std::size_t>(z) * static_cast<std::size_t>(cells[1]) +
                        static_cast<std::size_t>(y)) *
                           static_cast<std::size_t>(cells[0]) +
                       static_cast<std::size_t>(x);
    return clearance_of[code[index]];
  }

  // Whether `point` lies wholly inside: in a polyhedron of few faces, below every face;
  // otherwise in the core, or in a cell with c > 0.
  bool inside(const Vec3& point) const {
    const Vec3 o = point - core_centre;
    if (faces > 0) {
      for (int i = 0; i < faces; ++i) {
        if (!(face_x[i] * o.x() + face_y[i] * o.y() + face_z[i] * o.z() < face_offset[i])) {
          return false;
        }
      }
      return true;
    }
    return o.squaredNorm() < core_radius2 || at(point) > 0.0;
  }
};

class ObjectBoundary {
 public:
  static constexpr bool has_surface = true;
  static constexpr bool layered = false;

  // The object's surface, as random_walk.hpp has it, for a flight whose end the lanes did not
  // find wholly inside (the interior test made), and its light, as kernel.hpp has it.
  using Leaves = bool (*)(const void* object, Vec3& position, Vec3& direction, Vec3& next,
                          double flight, PhotonRandom& random, SurfaceExit& exit);
  using Launch = bool (*)(const void* light, PhotonRandom& random, Vec3& start, Vec3& heading);

  // `object` (convex), `light` and the grid `interior` reads outlive the boundary.
  ObjectBoundary(const void* object, Leaves object_leaves, const void* light, Launch light_launch,
                 const InteriorClearance& interior)
      : object_(object),
        leaves_(object_leaves),
        light_(light),
        launch_(light_launch),
        interior_(interior) {}

  bool leaves(Vec3& position, Vec3& direction, Vec3& next, double flight, PhotonRandom& random,
              SurfaceExit& exit) const {
    return leaves_(object_, position, direction, next, flight, random, exit);
  }
  bool launch(PhotonRandom& random, Vec3& start, Vec3& heading) const {
    return launch_(light_, random, start, heading);
  }

  const InteriorClearance& interior() const { return interior_; }

 private:
  const void* object_;
  Leaves leaves_;
  const void* light_;
  Launch launch_;
  InteriorClearance interior_;
};

}  // namespace scatterlab
