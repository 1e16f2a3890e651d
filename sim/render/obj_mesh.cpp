#include "obj_mesh.hpp"

#include <fmt/format.h>
#include <tiny_obj_loader.h>

#include <charconv>
#include <cmath>
#include <fstream>
#include <iterator>
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
void check_vertex_lines(const std::string& contents, const std::string& name) {
  std::istringstream in(contents);
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
            fmt::format("'{}' line {}: coordinate {} of '{}' is {}", name, number, c + 1,
                        tag, read ? "'" + text + "', not finite" : "missing"),
            "three finite decimal coordinates on every v and vn line");
      }
    }
  }
}

// A face corner's index into an array of `count` triples (positions or normals), checked: a file
// may name a vertex it does not have, and tinyobjloader passes the index on as it is.
std::size_t checked_index(int index, std::size_t count, const char* what, const std::string& name) {
  if (index < 0 || static_cast<std::size_t>(index) >= count) {
    throw InputError("mesh.path",
                     fmt::format("'{}': a face names {} {} but the file has {}", name, what,
                                 static_cast<long long>(index) + 1, count),
                     fmt::format("face indices within the file's {}s (1 to {})", what, count));
  }
  return static_cast<std::size_t>(index);
}

}  // namespace

TriangleMesh read_obj_mesh(const std::filesystem::path& path, bool interpolated_normals) {
  const std::string name = path.string();
  std::error_code code;
  if (!std::filesystem::is_regular_file(path, code)) {
    throw InputError("mesh.path", fmt::format("'{}' does not exist or is not a file", name),
                     "a readable Wavefront OBJ file");
  }
  std::ifstream in(path, std::ios::binary);
  std::string contents{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (!in && !in.eof()) {
    throw InputError("mesh.path", fmt::format("cannot read '{}'", name),
                     "a readable Wavefront OBJ file");
  }
  return parse_obj_mesh(contents, name, interpolated_normals);
}

TriangleMesh parse_obj_mesh(const std::string& text, const std::string& name,
                            bool interpolated_normals) {
  check_vertex_lines(text, name);
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  // From text, tinyobjloader ignores `mtllib`: a medium comes from the scene, and a mesh file
  // opens no other file.
  tinyobj::ObjReader reader;
  if (!reader.ParseFromString(text, "", config)) {
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
          const std::size_t v =
              checked_index(index.vertex_index, attrib.vertices.size() / 3, "vertex", name);
          mesh.positions.emplace_back(attrib.vertices[3 * v], attrib.vertices[3 * v + 1],
                                      attrib.vertices[3 * v + 2]);
          if (file_normals) {
            const std::size_t n =
                checked_index(normal, attrib.normals.size() / 3, "normal", name);
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
