#pragma once
// Wavefront OBJ meshes (tinyobjloader) as TriangleMesh: every shape of the file in one mesh,
// polygons triangulated, with the file's vertex normals when it has them and `interpolated`.

#include <filesystem>
#include <string>

#include "scatterlab/core/triangle_mesh.hpp"

namespace scatterlab {

// Throws InputError("mesh.path", ...) for a missing or unreadable file, a file without triangles,
// a face index outside the file's vertices or normals, or normals that are not one per position
// (after de-indexing), or not finite. `mtllib` lines are ignored: no other file is opened.
TriangleMesh read_obj_mesh(const std::filesystem::path& path, bool interpolated_normals);

// The same from the file's text; `name` stands for the file in messages.
TriangleMesh parse_obj_mesh(const std::string& text, const std::string& name,
                            bool interpolated_normals);

}  // namespace scatterlab
