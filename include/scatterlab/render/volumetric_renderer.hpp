#pragma once
// Volumetric path tracing of the whole light transport through a refractive mesh (method
// `volumetric`; Bitterli 2013, §3.2, Algorithm 1, extended to the scene around the object).
// From the camera, `samples` paths through each pixel centre:
//  outside    the nearest of the mesh, the floor and the sphere light (MeshRayTracer for the mesh,
//             analytic for the plane and the sphere); a path that leaves the scene sees the
//             environment radiance (0: black).
//  boundary   the smooth dielectric surface (core/fresnel.hpp): reflected with probability F,
//             refracted (Snell) otherwise, from either side, F = 1 under total internal
//             reflection (Algorithm 1, lines 6-10: the choice is analog, so no weight changes).
//             Radiance crossing into the medium gains eta^2 and loses it leaving (the n^2 law);
//             every path that scores leaves the medium as often as it entered (lights and floor
//             are outside), so the factors cancel and are not applied.
//  inside     a free flight t = -ln(xi) / sigma_t (line 3) against the distance to the boundary
//             (line 4); at a collision, absorption with probability 1 - albedo (line 15, analog)
//             and a new direction from the Henyey-Greenstein phase function (line 16).
//  colour     one path carries every channel, sampled with the medium of one "hero" channel
//             chosen at random (Wilkie et al. 2014, §4); channel c's weight is the balance
//             heuristic over the channels' strategies for the whole path, A_c / ((1/N)
//             sum_k p_k / p_c), with p_k the path's density under channel k's medium and A_c
//             the product of c's albedos. It is at most N A_c, however long the path. Absorption
//             is a roulette on the largest A_c: with one channel, the analog absorption above.
//  light      a path reaching the sphere light scores its radiance L_e = I / (pi r^2) (a
//             refractive boundary admits no shadow rays from inside: light reaches the medium
//             only along refracted paths, which the path finds by hitting the light).
//  floor      a Lambertian plane, albedo a: next-event estimation to the sphere light (a
//             direction uniform in the cone the sphere subtends, pdf 1 / (2 pi (1 - cos
//             theta_max)); the shadow ray is blocked by the object), plus a cosine-weighted
//             bounce (pdf cos / pi: the weight (a / pi) cos / pdf is a, then the roulette). No
//             double counting, no MIS: light reached by the bounce is scored only when a mesh event
//             lies between the floor and the light. The direct term of a floor point, L_d =
//             int_{light} (a / pi) L_e cos dω over the unoccluded part of the cone, is exactly what
//             next-event estimation estimates; every other path from the floor (through or off the
//             object, to the light or the environment) is estimated by the bounce alone. So each
//             path is counted by one estimator, and the sum is unbiased.
//  roulette   past volumetric_roulette_after collisions a path survives each further one
//             with probability 1/10 and its weight grows tenfold (Bitterli §3.2): unbiased, and
//             long paths in media of albedo near 1 are cut short.
// The random numbers of a path are a Philox stream keyed by (seed, pixel, sample), so an image is
// independent of the thread count. A scene with a single medium and a grey floor is traced as
// one channel and shown grey; a medium per channel (render_scene.hpp) or a coloured floor makes
// three. The standard error per pixel and channel is that of the mean of the `samples` paths.

#include <cstdint>

#include "scatterlab/core/work_pace.hpp"
#include "scatterlab/io/image.hpp"
#include "scatterlab/render/render_scene.hpp"
#include "scatterlab/render/single_scatter_renderer.hpp"

namespace scatterlab {

// Collisions after which Bitterli's roulette starts (well beyond the typical path in the shipped
// scenes: only rare long paths meet it).
inline constexpr int volumetric_roulette_after = 256;

struct VolumetricCounters {
  std::uint64_t paths = 0;        // traced (each carries every channel)
  std::uint64_t collisions = 0;   // scattering events in the medium
  std::uint64_t boundary = 0;     // reflections and refractions at the mesh
  std::uint64_t light_hits = 0;   // paths that scored by reaching the light
  std::uint64_t shadow_rays = 0;  // next-event estimates from the floor
  std::uint64_t lost = 0;         // paths rounding let through the mesh or off a grazing facet
};

struct VolumetricResult {
  RgbImage image;           // radiance, per channel
  RgbImage standard_error;  // of each pixel's mean, same units
  VolumetricCounters counters;
  double seconds = 0.0;
};

// settings.method must be volumetric (std::invalid_argument otherwise); uses settings.seed,
// threads and scattering_order. progress(tiles done, tiles) as render_single_scatter. Throws
// InputError for a point light (radius 0), and when the work or memory checks fail.
VolumetricResult render_volumetric(const RenderScene& scene, const RenderSettings& settings,
                                   const WorkProgress& progress = {});

}  // namespace scatterlab
