#pragma once
// A point cloud on a closed triangle mesh, and the light entering it at each point: the first
// pass of the hierarchical evaluation of a diffusion BSSRDF (Jensen & Buhler 2002; Bitterli 2013,
// §2.6.4 "Generating Sample Locations" and "First Pass: Irradiance Sampling", §3.3.1).
//
// Points: N points spread uniformly over the mesh by Turk's point repulsion (Turk 1992, as
// Bitterli §2.6.4 describes it): a random start, uniform by area (each point a triangle chosen
// with probability proportional to its area and a uniform point in it, from the Philox stream of
// (seed, point)), then `relaxation` iterations in which every point is pushed away from its
// neighbours closer than the repulsion radius r = 2 sqrt(A / N) with a force (r - d) along the
// line between them, the push projected onto the point's tangent plane, and the point moved to
// the nearest point of the mesh (walked across triangles that share a vertex with its own); a
// push over a sharp edge (facets more than 30 degrees apart) carries on down the face beyond it
// instead of stopping on the edge (Bitterli §2.6.4: points pushed off their face are "projected
// onto their neighbouring polygon"), so that a box's points do not gather on its edges. The
// iterations move every point from the previous positions at once, so the cloud is a function of
// the seed alone, whatever the thread count. Every point has the area A / N
// (Bitterli §2.6.4: p_a = A / |P|), so the areas sum to the mesh's area A.
//
// Irradiance: the power per unit area entering the medium at each point from the scene's light,
//   E_t(p) = sum_k F_t(eta, cos theta_k) cos theta_k I_k / d_k^2 V_k(p),
// over the light's points k (a point light is one; a sphere light is the disc of `light_samples`
// points the deterministic renderers use, single_scatter_renderer.hpp), theta_k the angle between
// the point's shading normal and the direction to the light point outside the medium, d_k the
// distance, F_t the dielectric Fresnel transmittance (core/fresnel.hpp) and V_k the visibility:
// an Embree occlusion ray from the point to the light point (self-occlusion; off: V = 1). It is
// Bitterli eq. 2.14's cos(theta_i) L_i dw_i for a point source with the BSSRDF's entry F_t, so
// that sum_p E_t(p) A_p R_d is the exitance the BSSRDF gives (eq. 2.16). Units: W / length^2 for
// I in W/sr, lengths in the mesh's unit.
//
// A directional light (the explorer's, Bitterli §3.1.2: a light the user rotates about the
// object) is the limit of a point light far away: a beam of irradiance E_0 normal to it arriving
// from the unit direction w_l, so that
//   E_t(p) = E_0 F_t(eta, cos theta_i) cos theta_i V(p),   cos theta_i = n(p) . w_l,
// with V the visibility along w_l (a shadow ray from p towards the light, unbounded).

#include <cstdint>
#include <vector>

#include "scatterlab/core/triangle_mesh.hpp"
#include "scatterlab/core/work_pace.hpp"
#include "scatterlab/render/render_scene.hpp"

namespace scatterlab {

struct PointCloudOptions {
  int points = 4096;       // N >= 1
  int relaxation = 40;     // Turk's repulsion iterations, >= 0
  std::uint64_t seed = 1;  // the random start's Philox key
  int threads = 0;         // of the relaxation; 0: all (the result does not depend on it)
};

struct PointCloud {
  std::vector<Vec3> positions;           // on the mesh
  std::vector<Vec3> normals;             // unit shading normals there (outward)
  std::vector<std::uint32_t> triangles;  // the triangle each lies on
  double point_area = 0.0;               // A / N, every point's
  double repulsion_radius = 0.0;         // 2 sqrt(A / N)

  std::size_t size() const { return positions.size(); }
};

// The largest point count a cloud may hold (memory: about 200 bytes per point with the octree's
// nodes and the per-point file, under a gigabyte; an image's cost grows with it too).
inline constexpr int max_cloud_points = 1 << 22;
inline constexpr int max_relaxation = 100000;

// Deterministic for a seed (and independent of the thread count). Throws InputError("points",
// ...) or ("relaxation", ...) for values out of range, and ("mesh", ...) for a mesh without area.
// progress(iterations done, relaxation) after each iteration.
PointCloud make_point_cloud(const TriangleMesh& mesh, const PointCloudOptions& options,
                            const WorkProgress& progress = {});

// The spread of the distances from each point to its nearest neighbour: their standard deviation
// over their mean (about 0.52 for points independent and uniform on a plane, 0 for a perfect
// lattice). The measure of uniformity the relaxation lowers.
double nearest_neighbour_spread(const PointCloud& cloud);

// E_t at every point (above), for the scene's light, eta and mesh. `occlusion`: trace the
// shadow rays (Embree); false: every point sees the light (a convex object needs none).
// threads: 0 uses all (the result does not depend on it).
std::vector<double> point_irradiance(const RenderScene& scene, const PointCloud& cloud,
                                     bool occlusion, int threads = 0);

struct DirectionalLight {
  Vec3 to_light = Vec3::UnitZ();  // towards the light (need not be unit; the light travels along
                                  // -to_light)
  double irradiance = 1.0;        // E_0, W / length^2 on a plane normal to the beam
};

// E_t at every point (above) for a directional light on `mesh` (the mesh the cloud was made on),
// eta = n_inside / n_outside. Throws InputError("light.direction", ...) for a zero direction.
std::vector<double> directional_irradiance(const TriangleMesh& mesh, const PointCloud& cloud,
                                           const DirectionalLight& light, double eta,
                                           bool occlusion, int threads = 0);

}  // namespace scatterlab
