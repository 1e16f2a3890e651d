#pragma once
// Images of an analytic diffusion BSSRDF on any closed mesh (method `bssrdf`): the hierarchical
// point cloud of Jensen & Buhler 2002 (Bitterli 2013, §2.6.4 and §3.3), in three steps:
//  1. a point cloud on the mesh with the power entering at each point from the scene's light
//     (point_cloud.hpp: Turk's repulsion, then E_t with self-occlusion by default);
//  2. the octree of those points (point_octree.hpp);
//  3. one eye ray per pixel centre (Embree); where it meets the mesh, at x_o, the exitance
//     M(x_o) = sum_p E_t A_p R_d(|x_o - p|) through the octree (clusters of solid angle below
//     `cluster_angle`), and the radiance leaving towards the camera
//       L_o = M(x_o) F_t(eta, cos theta_o) / (pi 4 C_phi(1/eta))       (Bitterli eq. 2.16
//     integrated over the cloud: models/bssrdf.hpp's bssrdf_exit_weight), theta_o the angle
//     between the eye ray and the shading normal at x_o.
// A medium per channel renders each channel with its own profile (the irradiance, which depends
// on eta alone, is shared). The exitance at every point of the cloud is returned too.
//
// What it renders: multiple scattering of a medium under a half-space diffusion model only; no
// single scattering, no light reflected off the surface, no floor (a scene with one is refused)
// and no light that reached the object other than straight from the light (occlusion by the
// object itself aside). Units: E_t and M in W / length^2, L_o in W / (sr length^2) for the
// light's I in W/sr and the mesh's length unit (the single-scatter methods' units).

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "scatterlab/core/work_pace.hpp"
#include "scatterlab/io/image.hpp"
#include "scatterlab/models/diffusion_profile.hpp"
#include "scatterlab/render/point_cloud.hpp"
#include "scatterlab/render/render_scene.hpp"

namespace scatterlab {

struct BssrdfSettings {
  ProfileModel model = ProfileModel::better_dipole;
  PointCloudOptions cloud;      // points, relaxation, seed
  double cluster_angle = 0.05;  // epsilon of eq. 2.40, sr; 0: every point summed
  bool occlusion = true;        // shadow rays from each point to the light (self-occlusion)
  int threads = 0;              // 0: all
};

struct BssrdfCounters {
  std::uint64_t eye_rays = 0;     // pixels whose ray met the mesh
  std::uint64_t evaluations = 0;  // R_d lookups for the image (points summed + clusters)
  std::uint64_t clusters = 0;     // octree nodes evaluated as one point for the image
  std::uint64_t lit_points = 0;   // points with E_t > 0
};

struct BssrdfResult {
  RgbImage image;  // radiance per channel (one channel repeated: grey)
  int channels = 1;
  PointCloud cloud;
  std::vector<double> irradiance;  // E_t per point, W / length^2
  std::vector<double> exitance;    // M per point and channel, [point][channel], W / length^2
  std::size_t octree_nodes = 0;
  int octree_depth = 0;
  BssrdfCounters counters;
  // Wall-clock seconds of each step (seconds_octree: the octree, the R_d tables and the eye
  // rays' Embree scene; seconds_image: the eye rays and the octree traversals alone).
  double seconds_cloud = 0.0, seconds_irradiance = 0.0, seconds_octree = 0.0, seconds_points = 0.0,
         seconds_image = 0.0;
  double seconds() const {
    return seconds_cloud + seconds_irradiance + seconds_octree + seconds_points + seconds_image;
  }
};

// Without clustering (cluster_angle 0) an image costs (pixels + points) x points evaluations:
// past max_render_evaluations (single_scatter_renderer.hpp: months of work) it is refused with
// InputError(field, ...). render_bssrdf checks it too.
void check_bssrdf_work(const RenderScene& scene, const BssrdfSettings& settings,
                       const std::string& field = "cluster_angle");

// Throws InputError for a scene with a floor, settings out of range ("points", "relaxation",
// "cluster_angle"), and a medium the profile refuses (naming its field). progress(steps done,
// steps): the relaxation's iterations, then the image's tiles of 8 x 8 pixels.
BssrdfResult render_bssrdf(const RenderScene& scene, const BssrdfSettings& settings,
                           const WorkProgress& progress = {});

// The per-point results as HDF5, written atomically: /points/{position, normal, area,
// irradiance, exitance} with units attributes, the settings and the scene's medium as attributes
// of /parameters.
void write_point_cloud_file(const std::filesystem::path& path, const RenderScene& scene,
                            const BssrdfSettings& settings, const BssrdfResult& result);

}  // namespace scatterlab
