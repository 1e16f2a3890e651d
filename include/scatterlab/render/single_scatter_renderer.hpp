#pragma once
// Single-scatter images of a refractive mesh (Walter et al. 2009, §5; Holzschuch 2013, §3-4).
// One eye ray per pixel centre: it refracts into the object at its first hit (Fresnel
// transmittance T_0, Snell), and the once-scattered radiance along the inside segment
// V(x) = P_0 + x w, x in [0, t_exit], is
//   L_camera = (T_0 / eta^2) int_0^t_exit sigma_s exp(-sigma_t x) S(V(x)) dx,
//   S(V) = sum over paths L -> P -> V of p(cos theta) I E(V),
// with E the irradiance per unit intensity of path_contribution (T eta^2 A / D exp(-sigma_t d_V),
// Walter eq. 17 with the eta^2 of etendue) and 1 / eta^2 the n^2 law of radiance leaving the
// medium. Units: radiance per unit light intensity times I, W / (sr length^2) for I in W/sr.
//
// Methods:
//  straight    Jensen et al. 2001, §4.3: the shadow ray goes straight from V to the light,
//              meeting the boundary after s at cosine mu; the light's refraction is approximated
//              by Jensen's refracted distance s' = s mu / mu_t (Snell's mu_t) and the refracted
//              direction in the phase function: E = I T(mu) exp(-sigma_t s') / |L - V|^2.
//  walter      `samples` points along the segment (midpoints of equal steps of the
//              transmittance exp(-sigma_t x)), every refracted path at each found with the
//              refractive solver (Walter §3), and counted when nothing of the boundary lies
//              across its leg inside (V to P) or its leg outside (P to the light): Walter §5
//              checks every path for occlusion, without which a shape that is not convex is
//              lit through itself. holzschuch counts its paths the same way.
//  holzschuch  support intervals per triangle (Holzschuch §3.2, find_segment_supports), and
//              `samples` points inside each interval; only that triangle is searched there.
//              With shared_points, walter's points instead, each searched only in the
//              triangles whose interval holds it: walter's sum to rounding.
//  pathtrace   Monte Carlo reference with the area light: a distance by the transmittance,
//              a direction by the phase function, traced to the boundary (Embree), Fresnel
//              transmitted and refracted out, and counted when it reaches the light sphere
//              unblocked (radiance T eta^2 I / (pi r^2)). Unbiased; the standard error per pixel
//              is returned.
// The deterministic methods see a sphere light of radius r as the disc it shows the object:
// centred on the light, facing the centre of the mesh's bounding box, cut into `light_samples`
// cells of equal area (Vogel's spiral), each an isotropic point light of intensity I / M. A
// uniform sphere seen from a point is exactly its disc facing that point; the one disc differs
// for points of the object off its axis by the tilt delta between the two, which moves the
// emitting points by at most r (1 - cos delta) (3e-3 r for the shipped scenes, delta <= 14
// degrees). One point is the sphere's centre: its far field.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "scatterlab/core/memory_budget.hpp"
#include "scatterlab/core/work_pace.hpp"
#include "scatterlab/render/image_file.hpp"
#include "scatterlab/render/render_scene.hpp"

namespace scatterlab {

//  volumetric  not a single-scatter method: every order of scattering, the floor and colour
//              (render/volumetric_renderer.hpp, render_volumetric); render_single_scatter
//              refuses it.
//  bssrdf      not a single-scatter method either: the multiple scattering of an analytic
//              diffusion BSSRDF, evaluated on a point cloud (render/bssrdf_renderer.hpp,
//              render_bssrdf); render_single_scatter refuses it.
enum class RenderMethod { straight, walter, holzschuch, pathtrace, volumetric, bssrdf };

// "straight", "walter", "holzschuch", "pathtrace", "volumetric", "bssrdf"; InputError("method",
// ...) otherwise.
RenderMethod parse_render_method(const std::string& name);
std::string to_string(RenderMethod method);

struct RenderSettings {
  RenderMethod method = RenderMethod::holzschuch;
  bool shared_points = false;  // holzschuch: walter's sample points (see above)
  std::uint64_t seed = 1;      // pathtrace, volumetric
  int threads = 0;             // 0: all
  // volumetric: 0 renders every order; n > 0 only the paths scattered exactly n times in the
  // medium (n = 1 with eta = 1 is what pathtrace estimates).
  int scattering_order = 0;
  // Tests only: take the general path (refraction, shading normals) even where the scene does
  // not need it, to check that the specialised one gives the same image.
  bool force_general = false;
};

// The points standing for the scene's light in the deterministic methods (see above): a point
// light is itself; a sphere light is the disc it shows `target`, cut into `count` cells of equal
// area (Vogel's spiral), each an isotropic point of intensity I / count.
struct LightPoint {
  Vec3 position;
  double intensity;  // W/sr
};
std::vector<LightPoint> light_points(const RenderLight& light, int count, const Vec3& target);

struct RenderCounters {
  std::uint64_t eye_rays = 0;       // pixels whose ray entered the object
  std::uint64_t point_queries = 0;  // points searched (shadow rays; holzschuch: per interval)
  std::uint64_t triangle_searches = 0;
  std::uint64_t paths = 0;          // refracted paths found (or light hits for pathtrace)
  std::uint64_t supports = 0;       // holzschuch: triangle intervals
  std::uint64_t blocked_paths = 0;  // walter, holzschuch: paths found but blocked by the mesh
};

struct RenderResult {
  Image image;           // radiance
  Image standard_error;  // pathtrace: per pixel (same units); zeros for the other methods
  RenderCounters counters;
  double seconds = 0.0;
};

// A render's work in point-light evaluations: pixels x samples per eye ray x light points (one
// point for pathtrace, which samples the light once per path; volumetric: a path per channel). Past
// max_render_evaluations a render takes months on one core (a microsecond or more per evaluation)
// and is refused before it starts, as simulate refuses more than 2^53 events: each size is in its
// range, their product is not.
inline constexpr std::uint64_t max_render_evaluations = std::uint64_t{1} << 42;
std::uint64_t render_evaluations(const RenderScene& scene, const RenderSettings& settings);
// Throws InputError naming the fields whose product is over max_render_evaluations.
void check_render_work(const RenderScene& scene, const RenderSettings& settings);

// What render_single_scatter holds at its peak: the image and its standard error, the light
// points and, for holzschuch, one light table per point (RefractedLight::table_bytes).
MemoryEstimate render_memory(const RenderScene& scene, const RenderSettings& settings);
// Throws InputError naming the image and light fields when render_memory does not fit.
void check_render_memory(const RenderScene& scene, const RenderSettings& settings);

// progress(tiles done, tiles) is called from one thread as tiles finish. Throws InputError for a
// pathtrace run with a point light (radius 0), and for one whose render_memory does not fit
// (core/memory_budget.hpp), before anything is allocated; std::invalid_argument for
// volumetric, and InputError for a scene with a medium per channel or a floor, which only
// volumetric renders.
RenderResult render_single_scatter(const RenderScene& scene, const RenderSettings& settings,
                                   const WorkProgress& progress = {});

}  // namespace scatterlab
