#include "scatterlab/core/triangle_mesh.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <map>
#include <stdexcept>

#include "scatterlab/core/error.hpp"

namespace scatterlab {

Vec3 TriangleMesh::corner_normal(std::size_t triangle, int corner) const {
  if (normals.empty()) return geometric_normal(triangle);
  return normals[triangles[triangle][static_cast<std::size_t>(corner)]];
}

Vec3 TriangleMesh::geometric_normal(std::size_t triangle) const {
  const Vec3 n =
      (vertex(triangle, 1) - vertex(triangle, 0)).cross(vertex(triangle, 2) - vertex(triangle, 0));
  const double length = n.norm();
  return length > 0.0 ? Vec3(n / length) : Vec3::Zero();
}

BoundingBox TriangleMesh::bounds() const {
  if (positions.empty()) return {};
  BoundingBox box{positions.front(), positions.front()};
  for (const Vec3& p : positions) {
    box.lo = box.lo.cwiseMin(p);
    box.hi = box.hi.cwiseMax(p);
  }
  return box;
}

double TriangleMesh::area(std::size_t triangle) const {
  return 0.5 * (vertex(triangle, 1) - vertex(triangle, 0))
                   .cross(vertex(triangle, 2) - vertex(triangle, 0))
                   .norm();
}

void TriangleMesh::validate() const {
  for (std::size_t i = 0; i < positions.size(); ++i) {
    if (!positions[i].allFinite()) {
      throw InputError("mesh.positions", fmt::format("vertex {} is not finite", i),
                       "finite coordinates");
    }
  }
  if (!normals.empty() && normals.size() != positions.size()) {
    throw InputError("mesh.normals",
                     fmt::format("{} normals for {} positions", normals.size(), positions.size()),
                     "no normals, or one per position");
  }
  for (std::size_t i = 0; i < normals.size(); ++i) {
    if (!normals[i].allFinite() || std::abs(normals[i].norm() - 1.0) > 1e-6) {
      throw InputError("mesh.normals", fmt::format("normal {} is not of unit length", i),
                       "unit vectors");
    }
  }
  if (triangles.empty()) throw InputError("mesh.triangles", "none given", "at least one");
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    for (const std::uint32_t index : triangles[t]) {
      if (index >= positions.size()) {
        throw InputError(
            "mesh.triangles",
            fmt::format("triangle {} uses vertex {} of {}", t, index, positions.size()),
            "indices below the number of positions");
      }
    }
  }
}

std::vector<std::uint32_t> vertex_ids_by_position(const TriangleMesh& mesh) {
  std::map<std::array<double, 3>, std::uint32_t> id_of;
  std::vector<std::uint32_t> id(mesh.positions.size());
  for (std::size_t k = 0; k < mesh.positions.size(); ++k) {
    const Vec3& p = mesh.positions[k];
    id[k] = id_of.try_emplace({p.x(), p.y(), p.z()}, static_cast<std::uint32_t>(id_of.size()))
                .first->second;
  }
  return id;
}

std::vector<std::array<std::uint32_t, 3>> triangles_across_edges(
    const TriangleMesh& mesh, const std::vector<std::uint32_t>& id) {
  const auto corner = [&](std::size_t t, int k) {
    return id[mesh.triangles[t][static_cast<std::size_t>(k % 3)]];
  };
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> owner;  // directed edge
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    for (int k = 0; k < 3; ++k) {
      owner[{corner(t, k), corner(t, k + 1)}] = static_cast<std::uint32_t>(t);
    }
  }
  std::vector<std::array<std::uint32_t, 3>> across(mesh.triangle_count());
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const auto found = owner.find({corner(t, k + 1), corner(t, k)});
      across[t][static_cast<std::size_t>(k)] = found == owner.end() ? no_triangle : found->second;
    }
  }
  return across;
}

std::vector<Vec3> area_weighted_vertex_normals(const TriangleMesh& mesh) {
  std::vector<Vec3> sums(mesh.positions.size(), Vec3::Zero());
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    // The unnormalised cross product is twice the area times the unit normal.
    const Vec3 weighted =
        (mesh.vertex(t, 1) - mesh.vertex(t, 0)).cross(mesh.vertex(t, 2) - mesh.vertex(t, 0));
    for (const std::uint32_t index : mesh.triangles[t]) sums[index] += weighted;
  }
  for (Vec3& n : sums) {
    const double length = n.norm();
    n = length > 0.0 ? Vec3(n / length) : Vec3::UnitZ();
  }
  return sums;
}

void append_mesh(TriangleMesh& mesh, const TriangleMesh& part, const Vec3& shift) {
  if (!mesh.positions.empty() && mesh.has_shading_normals() != part.has_shading_normals()) {
    throw std::invalid_argument("append_mesh: one mesh has shading normals and the other not");
  }
  const auto base = static_cast<std::uint32_t>(mesh.positions.size());
  for (const Vec3& p : part.positions) mesh.positions.push_back(p + shift);
  mesh.normals.insert(mesh.normals.end(), part.normals.begin(), part.normals.end());
  for (const auto& t : part.triangles) {
    mesh.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  }
}

}  // namespace scatterlab
