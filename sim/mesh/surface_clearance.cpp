#include "surface_clearance.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <limits>

namespace scatterlab {

SurfaceClearance::SurfaceClearance(const TriangleMesh& mesh, const MeshRayTracer& tracer,
                                   int cells) {
  const BoundingBox box = mesh.bounds();
  const Vec3 extent = box.hi - box.lo;
  const double side = std::max(extent.maxCoeff(), 1e-300) / cells;
  int* n = grid_.cells;
  // One cell of margin each way, so that the surface never lies on the grid's rim.
  grid_.lo = box.lo - Vec3::Constant(side);
  grid_.inverse_side = 1.0 / side;
  for (int a = 0; a < 3; ++a) n[a] = static_cast<int>(std::ceil(extent[a] / side)) + 2;
  const auto index = [n](int x, int y, int z) {
    return static_cast<std::size_t>((z * n[1] + y) * n[0] + x);
  };
  const auto cell_of = [&](double v, int axis) {
    return std::clamp(static_cast<int>(std::floor((v - grid_.lo[axis]) * grid_.inverse_side)), 0,
                      n[axis] - 1);
  };
  const auto in_grid = [n](int u, int v, int w) {
    return u >= 0 && v >= 0 && w >= 0 && u < n[0] && v < n[1] && w < n[2];
  };
  constexpr int unset = std::numeric_limits<int>::max();
  std::vector<int> steps(static_cast<std::size_t>(n[0]) * n[1] * n[2], unset);
  std::deque<std::array<int, 3>> front;
  // The cells each triangle may meet, marked.
  const double margin = 1e-6 * side;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const Vec3 &a = mesh.vertex(t, 0), &b = mesh.vertex(t, 1), &c = mesh.vertex(t, 2);
    const Vec3 normal = mesh.geometric_normal(t);
    const Vec3 lo = a.cwiseMin(b).cwiseMin(c) - Vec3::Constant(margin);
    const Vec3 hi = a.cwiseMax(b).cwiseMax(c) + Vec3::Constant(margin);
    const double reach = 0.5 * side * normal.cwiseAbs().sum() + margin;
    for (int z = cell_of(lo.z(), 2); z <= cell_of(hi.z(), 2); ++z) {
      for (int y = cell_of(lo.y(), 1); y <= cell_of(hi.y(), 1); ++y) {
        for (int x = cell_of(lo.x(), 0); x <= cell_of(hi.x(), 0); ++x) {
          const Vec3 centre = grid_.lo + (Vec3(x, y, z) + Vec3::Constant(0.5)) * side;
          if (!(std::abs(normal.dot(centre - a)) <= reach)) continue;
          int& s = steps[index(x, y, z)];
          if (s == unset) {
            s = 0;
            front.push_back({x, y, z});
          }
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
          if (!in_grid(u, v, w)) continue;
          int& s = steps[index(u, v, w)];
          if (s == unset) {
            s = next;
            front.push_back({u, v, w});
          }
        }
      }
    }
  }
  // The regions of unmarked cells (k >= 1), joined face to face: each is inside or outside as a
  // whole, as the parity of a ray from its first cell's centre says (a direction of no special
  // alignment, so that the ray does not run along an edge).
  const Vec3 probe = Vec3(0.5773, 0.6123, 0.5407).normalized();
  code_.assign(steps.size(), 0);
  std::vector<bool> seen(steps.size(), false);
  std::vector<std::array<int, 3>> region;
  for (int z = 0; z < n[2]; ++z) {
    for (int y = 0; y < n[1]; ++y) {
      for (int x = 0; x < n[0]; ++x) {
        if (steps[index(x, y, z)] < 1 || seen[index(x, y, z)]) continue;
        region.assign(1, {x, y, z});
        seen[index(x, y, z)] = true;
        for (std::size_t r = 0; r < region.size(); ++r) {
          const auto [u, v, w] = region[r];
          for (const auto& [du, dv, dw] : {std::array<int, 3>{1, 0, 0}, {-1, 0, 0}, {0, 1, 0},
                                           {0, -1, 0}, {0, 0, 1}, {0, 0, -1}}) {
            const int a = u + du, b = v + dv, c = w + dw;
            if (!in_grid(a, b, c) || steps[index(a, b, c)] < 1 || seen[index(a, b, c)]) continue;
            seen[index(a, b, c)] = true;
            region.push_back({a, b, c});
          }
        }
        const Vec3 centre = grid_.lo + (Vec3(x, y, z) + Vec3::Constant(0.5)) * side;
        if (tracer.count_crossings(centre, probe) % 2 == 0) continue;
        for (const auto& [u, v, w] : region) {
          code_[index(u, v, w)] = static_cast<std::uint8_t>(std::min(steps[index(u, v, w)], 255));
        }
      }
    }
  }
  for (int k = 1; k < 256; ++k) {
    const double bound = std::max((k - 1.0) * side, margin) * (1.0 - 1e-6);
    clearance_of_[k] = static_cast<float>(bound);
    if (clearance_of_[k] > bound) clearance_of_[k] = std::nextafter(clearance_of_[k], 0.0f);
  }
  grid_.code = code_.data();
  grid_.clearance_of = clearance_of_;
}

}  // namespace scatterlab
