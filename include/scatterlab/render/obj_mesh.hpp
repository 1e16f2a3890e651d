#pragma once
// Wavefront OBJ meshes (tinyobjloader) as TriangleMesh: every shape of the file in one mesh,
// polygons triangulated, with the file's vertex normals when it has them and `interpolated`.

#include <filesystem>

#include "scatterlab/core/triangle_mesh.hpp"

namespace scatterlab {

// Throws InputError("mesh.path", ...) for a missing or unreadable file, a file without triangles,
// or normals that are not one per position (after de-indexing), or not finite.
TriangleMesh read_obj_mesh(const std::filesystem::path& path, bool interpolated_normals);

}  // namespace scatterlab
