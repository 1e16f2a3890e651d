#pragma once
// A render scene: a closed triangle mesh bounding a homogeneous refractive medium, a point light
// (optionally a small uniformly emitting sphere: the area light of the path-traced reference),
// and a pinhole camera. Read strictly from TOML (the scene reader's rules: unknown keys, wrong
// types and out-of-range values are one InputError naming the dotted key):
//
//   [mesh]    shape = "sphere" | "bumpy_sphere" | "rounded_tile" | "box" | "obj"
//             path = "file.obj"            (shape = "obj"; relative to the scene file)
//             normals = "interpolated" | "flat"
//             radius, amplitude, frequency, rings, segments   (sphere, bumpy_sphere)
//             half_size = [x, y, z], exponent, rings, segments (rounded_tile; box: half_size)
//   [medium]  sigma_s, sigma_a (1/length), g (HG), eta (n_inside / n_outside); sigma_s,
//             sigma_a and g may each be [red, green, blue] (one medium per channel: three
//             channels, rendered by method volumetric only), or
//             material = "NAME" (a measured medium of data/materials/, io/material_presets.hpp:
//             all three channels) with length_unit = "um" | "mm" | "cm" | "m" (the unit of the
//             scene's lengths; the table's by default), optional g and eta (the table's)
//   [floor]   height (z of a horizontal plane below everything), albedo (Lambertian: a number or
//             [red, green, blue] in [0, 1]); seen by method volumetric only
//   [light]   position = [x, y, z], intensity (W/sr), radius (0: a point light)
//   [camera]  position, look_at, up = [x, y, z], fov (vertical, degrees)
//   [image]   width, height, samples (per eye ray), light_samples (area light points)

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "scatterlab/core/frame.hpp"
#include "scatterlab/core/medium.hpp"
#include "scatterlab/core/triangle_mesh.hpp"

namespace scatterlab {

// A diffuse (Lambertian) floor: the plane z = height, facing up, reflecting albedo / pi per
// steradian of the irradiance it receives, per channel.
struct RenderFloor {
  double height = -1.0;
  std::array<double, 3> albedo = {0.5, 0.5, 0.5};  // red, green, blue in [0, 1]
};

struct RenderLight {
  Vec3 position = Vec3(0.0, 0.0, 4.0);
  double intensity = 1.0;  // W/sr of the point light; the sphere of `radius` has power 4 pi I
  double radius = 0.0;     // > 0: a sphere of uniform radiance I / (pi radius^2)
};

struct PinholeCamera {
  Vec3 position = Vec3(0.0, -4.0, 0.0);
  Vec3 look_at = Vec3::Zero();
  Vec3 up = Vec3::UnitZ();
  double fov_degrees = 30.0;  // vertical field of view

  // Unit direction through the centre of pixel (i, j) of a width x height image (row j = 0 on
  // top). Throws nothing; the scene checks the camera once.
  Vec3 ray_direction(int i, int j, int width, int height) const;
};

// The documented ranges of a render's sizes, from the scene file and the flags alike: an image
// side of 16384 pixels is a 268-megapixel image already, and past these budgets a single image
// runs for days without becoming more accurate than the methods themselves.
inline constexpr int max_image_side = 16384;
inline constexpr int max_samples = 1 << 20;     // per eye ray (or per support interval)
inline constexpr int max_light_samples = 4096;  // points on the area light

struct RenderScene {
  TriangleMesh mesh;                // closed, consistently oriented, validated
  std::filesystem::path mesh_file;  // the OBJ file it was read from; empty for a built-in shape
  Medium medium;                    // sigma_t, albedo, g (length unit: that of the mesh)
  // Empty: one channel, `medium`. Otherwise the red, green and blue media (`medium` is then the
  // green one), rendered by method volumetric as three channels.
  std::vector<Medium> channel_media;
  double eta = 1.5;  // n_inside / n_outside
  std::optional<RenderFloor> floor;
  // Radiance arriving from every direction that leaves the scene, in the image's units
  // ([environment] radiance; method volumetric only; 0: black).
  double environment_radiance = 0.0;
  RenderLight light;
  PinholeCamera camera;
  int width = 64, height = 64;
  int samples = 32;        // points along each eye ray (per support interval for holzschuch)
  int light_samples = 16;  // points on the area light for the deterministic methods

  // Checks what the mesh alone cannot: a closed mesh (every edge shared by exactly two triangles
  // in opposite directions) with no triangle of zero area that encloses a positive volume, the
  // light and the camera outside it, sizes within their ranges; a floor below the mesh, the
  // light and the camera. Throws InputError.
  void validate() const;
};

// The floor and the environment light only the volumetric method's paths: any other method
// refuses them (InputError naming the table) rather than leave them out of its image.
void refuse_volumetric_only(const RenderScene& scene, const std::string& method);

// The [mesh] table of any scene file (a lit object's, transport/lit_object.hpp), read as a render
// scene's is, and what it is in words: the shape and its triangle count, or the OBJ file. Other
// tables are left to the scene's own reader.
struct SceneMesh {
  TriangleMesh mesh;
  std::string source;
};
SceneMesh load_scene_mesh(const std::filesystem::path& scene);
// The same from a TOML text holding a [mesh] table (the explorer's meshes); `base` resolves
// relative OBJ paths.
SceneMesh parse_scene_mesh(std::string_view toml_text, const std::string& origin,
                           const std::filesystem::path& base = {});

// `base` resolves relative OBJ paths.
RenderScene parse_render_scene(std::string_view toml_text, const std::string& origin,
                               const std::filesystem::path& base = {});
RenderScene load_render_scene(const std::filesystem::path& path);

}  // namespace scatterlab
