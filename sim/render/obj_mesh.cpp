#include "scatterlab/render/obj_mesh.hpp"

#include <fmt/format.h>
#include <tiny_obj_loader.h>

#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <utility>

#include "scatterlab/core/error.hpp"

namespace scatterlab {

namespace {

// tinyobjloader reads a number it cannot parse ("nan", "inf", "1e999", "x") as 0, which would
// move a vertex silently: every vertex line is read here first, and each of its coordinates must
// be a finite decimal number.
void check_vertex_lines(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::string line;
  for (std::size_t number = 1; std::getline(in, line); ++number) {
    std::istringstream fields(line);
    std::string tag;
    if (!(fields >> tag) || (tag != "v" && tag != "vn")) continue;
    std::string text;
    for (int c = 0; c < 3; ++c) {
      double value = 0.0;
      const bool read = static_cast<bool>(fields >> text);
      const auto [end, error] =
          read ? std::from_chars(text.data(), text.data() + text.size(), value)
               : std::from_chars_result{text.data(), std::errc::invalid_argument};
      if (!read || error != std::errc{} || end != text.data() + text.size() ||
          !std::isfinite(value)) {
        throw InputError(
            "mesh.path",
            fmt::format("'{}' line {}: coordinate {} of '{}' is {}", path.string(), number, c + 1,
                        tag, read ? "'" + text + "', not finite" : "missing"),
            "three finite decimal coordinates on every v and vn line");
      }
    }
  }
}

}  // namespace

TriangleMesh read_obj_mesh(const std::filesystem::path& path, bool interpolated_normals) {
  const std::string name = path.string();
  std::error_code code;
  if (!std::filesystem::is_regular_file(path, code)) {
    throw InputError("mesh.path", fmt::format("'{}' does not exist or is not a file", name),
                     "a readable Wavefront OBJ file");
  }
  check_vertex_lines(path);
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  config.mtl_search_path = path.parent_path().string();
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(name, config)) {
    throw InputError("mesh.path", fmt::format("cannot read '{}': {}", name, reader.Error()),
                     "a readable Wavefront OBJ file");
  }
  const auto& attrib = reader.GetAttrib();
  const bool file_normals = interpolated_normals && !attrib.normals.empty();
  TriangleMesh mesh;
  // One mesh vertex per (position, normal) pair of the file.
  std::map<std::pair<int, int>, std::uint32_t> vertex_of;
  for (const auto& shape : reader.GetShapes()) {
    const auto& indices = shape.mesh.indices;
    for (std::size_t f = 0; f + 2 < indices.size(); f += 3) {
      std::array<std::uint32_t, 3> triangle{};
      for (std::size_t c = 0; c < 3; ++c) {
        const auto& index = indices[f + c];
        const int normal = file_normals ? index.normal_index : -1;
        if (file_normals && normal < 0) {
          throw InputError("mesh.path",
                           fmt::format("'{}': a face corner has no normal while others do", name),
                           "normals on every face corner, or none");
        }
        const auto key = std::make_pair(index.vertex_index, normal);
        auto [it, inserted] =
            vertex_of.try_emplace(key, static_cast<std::uint32_t>(mesh.positions.size()));
        if (inserted) {
          const auto v = static_cast<std::size_t>(index.vertex_index);
          mesh.positions.emplace_back(attrib.vertices[3 * v], attrib.vertices[3 * v + 1],
                                      attrib.vertices[3 * v + 2]);
          if (file_normals) {
            const auto n = static_cast<std::size_t>(normal);
            const Vec3 value(attrib.normals[3 * n], attrib.normals[3 * n + 1],
                             attrib.normals[3 * n + 2]);
            const double length = value.norm();
            if (!std::isfinite(length) || length == 0.0) {
              throw InputError("mesh.path",
                               fmt::format("'{}': normal {} is not finite or zero", name, n + 1),
                               "finite, non-zero vertex normals");
            }
            mesh.normals.push_back(value / length);
          }
        }
        triangle[c] = it->second;
      }
      mesh.triangles.push_back(triangle);
    }
  }
  if (mesh.triangles.empty()) {
    throw InputError("mesh.path", fmt::format("'{}' has no faces", name),
                     "a Wavefront OBJ file with triangles or polygons");
  }
  if (interpolated_normals && !file_normals) mesh.normals = area_weighted_vertex_normals(mesh);
  return mesh;
}

}  // namespace scatterlab
