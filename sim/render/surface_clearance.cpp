#include "scatterlab/render/surface_clearance.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <limits>

namespace scatterlab {

SurfaceClearance::SurfaceClearance(const TriangleMesh& mesh, int cells) {
  const BoundingBox box = mesh.bounds();
  const Vec3 extent = box.hi - box.lo;
  const double side = std::max(extent.maxCoeff(), 1e-300) / cells;
  // One cell of margin each way, so that the surface never lies on the grid's rim.
  lo_ = box.lo - Vec3::Constant(side);
  inverse_side_ = 1.0 / side;
  for (int a = 0; a < 3; ++a) n_[a] = static_cast<int>(std::ceil(extent[a] / side)) + 2;
  const auto index = [this](int x, int y, int z) {
    return static_cast<std::size_t>((z * n_[1] + y) * n_[0] + x);
  };
  const auto cell_of = [this](double v, int axis) {
    return std::clamp(static_cast<int>(std::floor((v - lo_[axis]) * inverse_side_)), 0,
                      n_[axis] - 1);
  };
  constexpr int unset = std::numeric_limits<int>::max();
  std::vector<int> steps(static_cast<std::size_t>(n_[0]) * n_[1] * n_[2], unset);
  std::deque<std::array<int, 3>> front;
  // Points on each triangle no farther than h / 2 from any of its points (a grid of spacing h / 2
  // in its barycentric parameters along its longest edges); each marks its cell.
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const Vec3 &a = mesh.vertex(t, 0), &b = mesh.vertex(t, 1), &c = mesh.vertex(t, 2);
    const double longest = std::max({(b - a).norm(), (c - a).norm(), (c - b).norm()});
    const int m = std::max(1, static_cast<int>(std::ceil(2.0 * longest / side)));
    for (int i = 0; i <= m; ++i) {
      for (int j = 0; i + j <= m; ++j) {
        const Vec3 p =
            a + (static_cast<double>(i) / m) * (b - a) + (static_cast<double>(j) / m) * (c - a);
        const int x = cell_of(p.x(), 0), y = cell_of(p.y(), 1), z = cell_of(p.z(), 2);
        int& s = steps[index(x, y, z)];
        if (s == unset) {
          s = 0;
          front.push_back({x, y, z});
        }
      }
    }
  }
  // Breadth first over the 26 neighbours: the Chebyshev distance to the nearest marked cell.
  while (!front.empty()) {
    const auto [x, y, z] = front.front();
    front.pop_front();
    const int next = steps[index(x, y, z)] + 1;
    for (int dz = -1; dz <= 1; ++dz) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const int u = x + dx, v = y + dy, w = z + dz;
          if (u < 0 || v < 0 || w < 0 || u >= n_[0] || v >= n_[1] || w >= n_[2]) continue;
          int& s = steps[index(u, v, w)];
          if (s == unset) {
            s = next;
            front.push_back({u, v, w});
          }
        }
      }
    }
  }
  steps_.resize(steps.size());
  for (std::size_t k = 0; k < steps.size(); ++k) {
    steps_[k] = static_cast<std::uint8_t>(std::min(steps[k], 255));
  }
  for (int k = 2; k < 256; ++k) clearance_of_[k] = (k - 1.5) * side * (1.0 - 1e-6);
}

}  // namespace scatterlab
