#include "scatterlab/core/procedural_meshes.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <functional>

#include "scatterlab/core/constants.hpp"
#include "scatterlab/core/error.hpp"

namespace scatterlab {
namespace {

// A closed surface given by position(theta, phi) on a latitude-longitude grid: a vertex at each
// pole, rings - 1 latitude circles of `segments` vertices, fans at the poles. Triangles are
// counter-clockwise seen from outside when position(theta, phi) is outward for growing theta
// towards the south pole and growing phi eastwards (as for a sphere).
TriangleMesh latitude_longitude_mesh(const std::function<Vec3(double, double)>& position,
                                     int rings, int segments) {
  if (rings < 2) throw InputError("mesh.rings", "fewer than 2", "an integer >= 2");
  if (segments < 3) throw InputError("mesh.segments", "fewer than 3", "an integer >= 3");
  TriangleMesh mesh;
  const auto u = [](int i) { return static_cast<std::uint32_t>(i); };
  mesh.positions.push_back(position(0.0, 0.0));
  for (int i = 1; i < rings; ++i) {
    const double theta = pi * i / rings;
    for (int j = 0; j < segments; ++j) {
      mesh.positions.push_back(position(theta, 2.0 * pi * j / segments));
    }
  }
  mesh.positions.push_back(position(pi, 0.0));
  const int south = static_cast<int>(mesh.positions.size()) - 1;
  const auto ring_vertex = [&](int i, int j) { return 1 + (i - 1) * segments + j % segments; };
  for (int j = 0; j < segments; ++j) {
    mesh.triangles.push_back({0u, u(ring_vertex(1, j)), u(ring_vertex(1, j + 1))});
  }
  for (int i = 1; i + 1 < rings; ++i) {
    for (int j = 0; j < segments; ++j) {
      const auto a = u(ring_vertex(i, j)), b = u(ring_vertex(i, j + 1));
      const auto c = u(ring_vertex(i + 1, j)), d = u(ring_vertex(i + 1, j + 1));
      mesh.triangles.push_back({a, c, d});
      mesh.triangles.push_back({a, d, b});
    }
  }
  for (int j = 0; j < segments; ++j) {
    mesh.triangles.push_back(
        {u(ring_vertex(rings - 1, j)), u(south), u(ring_vertex(rings - 1, j + 1))});
  }
  return mesh;
}

Vec3 unit_sphere(double theta, double phi) {
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

}  // namespace

TriangleMesh make_sphere(double radius, int rings, int segments, bool smooth_normals) {
  TriangleMesh mesh = latitude_longitude_mesh(
      [radius](double theta, double phi) { return Vec3(radius * unit_sphere(theta, phi)); },
      rings, segments);
  if (smooth_normals) {
    for (const Vec3& p : mesh.positions) mesh.normals.push_back(p.normalized());
  }
  return mesh;
}

TriangleMesh make_bumpy_sphere(double radius, double amplitude, int frequency, int rings,
                               int segments) {
  TriangleMesh mesh = latitude_longitude_mesh(
      [=](double theta, double phi) {
        const double r = radius * (1.0 + amplitude * std::sin(frequency * theta) *
                                             std::cos(frequency * phi));
        return Vec3(r * unit_sphere(theta, phi));
      },
      rings, segments);
  mesh.normals = area_weighted_vertex_normals(mesh);
  return mesh;
}

TriangleMesh make_rounded_tile(double half_x, double half_y, double half_z, double exponent,
                               int rings, int segments) {
  // Signed power keeps the octant: the superellipsoid's standard parameterisation.
  const auto signed_power = [exponent](double v) {
    return std::copysign(std::pow(std::abs(v), exponent), v);
  };
  TriangleMesh mesh = latitude_longitude_mesh(
      [=](double theta, double phi) {
        const double s = signed_power(std::sin(theta));
        return Vec3(half_x * s * signed_power(std::cos(phi)),
                    half_y * s * signed_power(std::sin(phi)),
                    half_z * signed_power(std::cos(theta)));
      },
      rings, segments);
  mesh.normals = area_weighted_vertex_normals(mesh);
  return mesh;
}

TriangleMesh make_flat_square(double half_width, int up) {
  TriangleMesh mesh;
  const double w = half_width;
  mesh.positions = {Vec3(-w, -w, 0), Vec3(w, -w, 0), Vec3(w, w, 0), Vec3(-w, w, 0)};
  if (up > 0) {
    mesh.triangles = {{0u, 1u, 2u}, {0u, 2u, 3u}};
  } else {
    mesh.triangles = {{0u, 2u, 1u}, {0u, 3u, 2u}};
  }
  return mesh;
}

TriangleMesh make_box(const Vec3& h) {
  TriangleMesh mesh;
  for (int k = 0; k < 8; ++k) {
    mesh.positions.emplace_back((k & 1) ? h.x() : -h.x(), (k & 2) ? h.y() : -h.y(),
                                (k & 4) ? h.z() : -h.z());
  }
  // Counter-clockwise seen from outside: quads (a, b, c, d) split into (a, b, c), (a, c, d).
  const std::array<std::array<std::uint32_t, 4>, 6> faces{
      {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}}};
  for (const auto& f : faces) {
    mesh.triangles.push_back({f[0], f[1], f[2]});
    mesh.triangles.push_back({f[0], f[2], f[3]});
  }
  return mesh;
}


}  // namespace scatterlab
