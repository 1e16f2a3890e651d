#include "scatterlab/render/volumetric_renderer.hpp"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "scatterlab/core/constants.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/core/fresnel.hpp"
#include "scatterlab/core/phase_function.hpp"
#include "scatterlab/core/random.hpp"
#include "scatterlab/render/mesh_ray_tracer.hpp"

namespace scatterlab {
namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();

// Bitterli 2013, §3.2: past the threshold a path survives each collision with probability 1/10
// and carries ten times the weight.
constexpr double roulette_survival = 0.1;

// Distance along unit `w` from `p` (outside the sphere) to the sphere (centre c, radius r), or
// infinity when the ray misses it.
double distance_to_light(const Vec3& p, const Vec3& w, const Vec3& c, double r) {
  const Vec3 oc = p - c;
  const double b = oc.dot(w);
  const double disc = b * b - (oc.squaredNorm() - r * r);
  if (disc < 0.0) return infinity;
  const double t = -b - std::sqrt(disc);
  return t > 0.0 ? t : infinity;
}

// One channel's medium and the scene pieces a path needs.
struct Channel {
  double sigma_t, albedo;
  HenyeyGreenstein phase;
  double floor_albedo;
};

class VolumetricTracer {
 public:
  VolumetricTracer(const RenderScene& scene, const RenderSettings& settings)
      : scene_(scene),
        settings_(settings),
        tracer_(scene.mesh),
        light_radiance_(scene.light.intensity / (pi * scene.light.radius * scene.light.radius)) {}

  void render(VolumetricResult& result, const WorkProgress& progress) {
    const bool colour = !scene_.channel_media.empty();
    std::vector<Channel> channels;
    for (std::size_t c = 0; c < (colour ? 3u : 1u); ++c) {
      const Medium& m = colour ? scene_.channel_media[c] : scene_.medium;
      channels.push_back({m.sigma_t, m.albedo, HenyeyGreenstein{m.g},
                          scene_.floor ? scene_.floor->albedo[c] : 0.0});
    }
    if (!colour && scene_.floor) {
      // One medium traced once: the floor's albedo must be one number too, or the channels
      // would differ after all.
      const auto& a = scene_.floor->albedo;
      if (a[0] != a[1] || a[1] != a[2]) {
        throw InputError("floor.albedo", "one per channel with a single medium",
                         "one number, or a medium per channel");
      }
    }
    const int tile = 8;
    const int tiles_x = (scene_.width + tile - 1) / tile;
    const int tiles_y = (scene_.height + tile - 1) / tile;
    const int tiles = tiles_x * tiles_y;
    const int threads = settings_.threads > 0 ? settings_.threads : omp_get_max_threads();
    std::vector<VolumetricCounters> counters(
        static_cast<std::size_t>(std::max(threads, omp_get_max_threads())));
    std::atomic<int> done{0};
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
    for (int t = 0; t < tiles; ++t) {
      VolumetricCounters& count = counters[static_cast<std::size_t>(omp_get_thread_num())];
      const int x0 = (t % tiles_x) * tile, y0 = (t / tiles_x) * tile;
      for (int j = y0; j < std::min(y0 + tile, scene_.height); ++j) {
        for (int i = x0; i < std::min(x0 + tile, scene_.width); ++i) {
          const Vec3 d = scene_.camera.ray_direction(i, j, scene_.width, scene_.height);
          const auto pixel = static_cast<std::uint64_t>(j) * scene_.width + i;
          for (std::size_t c = 0; c < channels.size(); ++c) {
            double mean = 0.0, error = 0.0;
            pixel_value(channels[c], d, pixel, mean, error, count);
            for (std::size_t k = colour ? c : 0; k < (colour ? c + 1 : 3); ++k) {
              result.image.channels[k].at(i, j) = mean;
              result.standard_error.channels[k].at(i, j) = error;
            }
          }
        }
      }
      const int finished = ++done;
      if (progress && omp_get_thread_num() == 0) {
        progress(static_cast<std::uint64_t>(finished), static_cast<std::uint64_t>(tiles));
      }
    }
    for (const auto& c : counters) {
      result.counters.paths += c.paths;
      result.counters.collisions += c.collisions;
      result.counters.boundary += c.boundary;
      result.counters.light_hits += c.light_hits;
      result.counters.shadow_rays += c.shadow_rays;
      result.counters.lost += c.lost;
    }
  }

 private:
  // The mean of `samples` paths from the camera along d, and its standard error.
  void pixel_value(const Channel& channel, const Vec3& d, std::uint64_t pixel, double& mean,
                   double& error, VolumetricCounters& count) const {
    const int n = scene_.samples;
    double sum = 0.0, sum2 = 0.0;
    for (int s = 0; s < n; ++s) {
      // (seed, pixel, sample): samples <= 2^20 (render_scene.hpp), pixels <= 2^28. The channels
      // share the stream: their paths part only where their media differ, so the noise of a
      // pixel is alike in the three (grey grain, not coloured speckle).
      PhotonRandom random(settings_.seed, (pixel << 20) | static_cast<std::uint64_t>(s));
      const double f = trace(channel, scene_.camera.position, d, random, count);
      sum += f;
      sum2 += f * f;
    }
    mean = sum / n;
    const double variance = n > 1 ? std::max(0.0, sum2 / n - mean * mean) / (n - 1) : 0.0;
    error = std::sqrt(variance);
  }

  Vec3 point_at(const MeshHit& hit) const {
    const TriangleMesh& mesh = scene_.mesh;
    return (1.0 - hit.bary_a - hit.bary_b) * mesh.vertex(hit.triangle, 0) +
           hit.bary_a * mesh.vertex(hit.triangle, 1) + hit.bary_b * mesh.vertex(hit.triangle, 2);
  }

  // The shading normal (outward) where the mesh has one, the facet's otherwise. A shading normal
  // that puts the ray on the other side than the facet does is replaced by the facet's, so that
  // the side a ray meets and the side the normal says agree.
  Vec3 normal_at(const MeshHit& hit, const Vec3& d) const {
    const TriangleMesh& mesh = scene_.mesh;
    const Vec3 geometric = mesh.geometric_normal(hit.triangle);
    if (!mesh.has_shading_normals()) return geometric;
    const double w0 = 1.0 - hit.bary_a - hit.bary_b;
    const Vec3 shading = (w0 * mesh.corner_normal(hit.triangle, 0) +
                          hit.bary_a * mesh.corner_normal(hit.triangle, 1) +
                          hit.bary_b * mesh.corner_normal(hit.triangle, 2))
                             .normalized();
    return (shading.dot(d) > 0.0) == (geometric.dot(d) > 0.0) ? shading : geometric;
  }

  // Reflection or refraction at the mesh, chosen with the Fresnel reflectance (Bitterli
  // Algorithm 1, lines 6-10, from either side). `inside` flips on refraction. False when the
  // new direction is on the wrong side of the facet (a shading normal's artefact: the path ends).
  bool cross_boundary(const MeshHit& hit, Vec3& d, bool& inside, double xi) const {
    const Vec3 n = normal_at(hit, d);           // outward
    const Vec3 facing = inside ? Vec3(-n) : n;  // towards the side the ray comes from
    const double eta = inside ? 1.0 / scene_.eta : scene_.eta;  // n_transmitted / n_incident
    const double cos_i = -d.dot(facing);
    if (!(cos_i > 0.0)) return false;  // met the facet from the side it should not have
    const double reflectance = fresnel_dielectric_reflectance(cos_i, eta);
    Vec3 next;
    bool crossed = false;
    if (xi < reflectance || !refract(d, facing, eta, next)) {
      next = d + 2.0 * cos_i * facing;  // mirror reflection (also total internal reflection)
    } else {
      crossed = true;
    }
    // The facet's normal decides which side the new direction is on.
    const double side = next.dot(scene_.mesh.geometric_normal(hit.triangle));
    const bool goes_out = side > 0.0;
    const bool now_inside = crossed ? !inside : inside;
    if (goes_out == now_inside) return false;
    d = next;
    inside = now_inside;
    return true;
  }

  // Next-event estimate of the light's direct radiance off the floor point x, per unit of the
  // path's weight: uniform in the cone of the sphere light (pbrt-v4 §12.2.3), so that
  //   L_d ~ (a / pi) L_e cos theta / pdf = 2 a L_e cos theta (1 - cos theta_max),
  // and 0 when the object blocks the shadow ray.
  double floor_direct(const Vec3& x, double albedo, PhotonRandom& random,
                      VolumetricCounters& count) const {
    const Vec3 to_centre = scene_.light.position - x;
    const double dist = to_centre.norm();
    const double sin2_max = std::min(1.0, std::pow(scene_.light.radius / dist, 2));
    const double cos_max = std::sqrt(1.0 - sin2_max);
    const double one_minus_cos_max = sin2_max / (1.0 + cos_max);  // no cancellation
    const auto u = random.next4();
    const double cos_theta = 1.0 - u[0] * one_minus_cos_max;
    const double sin_theta = std::sqrt(std::max(0.0, (1.0 - cos_theta) * (1.0 + cos_theta)));
    const double phi = 2.0 * pi * u[1];
    const Vec3 w = Frame(to_centre / dist)
                       .to_world(sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta);
    const double cos_floor = w.z();
    if (!(cos_floor > 0.0)) return 0.0;
    ++count.shadow_rays;
    const double t = distance_to_light(x, w, scene_.light.position, scene_.light.radius);
    // Rounding can miss the sphere at the cone's rim; the tangent distance stands in.
    const double t_light = std::isfinite(t) ? t : dist * cos_max;
    if (tracer_.occluded(x, w, 0.0, t_light)) return 0.0;
    return 2.0 * albedo * light_radiance_ * cos_floor * one_minus_cos_max;
  }

  // One path from `origin` along `d`: the radiance it carries back, times its weight.
  double trace(const Channel& channel, Vec3 origin, Vec3 d, PhotonRandom& random,
               VolumetricCounters& count) const {
    ++count.paths;
    const RenderLight& light = scene_.light;
    const int order = settings_.scattering_order;
    double weight = 1.0, t_near = 0.0, radiance = 0.0;
    bool inside = false;
    bool after_floor = false;  // nothing but the floor's bounce since the last floor point
    int collisions = 0;
    // Every branch ends the path or moves it on; a path lives until it leaves, is absorbed or
    // loses the roulette.
    for (;;) {
      const auto u = random.next4();
      MeshHit hit;
      const bool hits_mesh = tracer_.intersect(origin, d, t_near, infinity, hit);
      if (inside) {
        if (!hits_mesh) {  // rounding let the path slip through the mesh
          ++count.lost;
          return radiance;
        }
        const double flight = -std::log(u[0]) / channel.sigma_t;  // Algorithm 1, line 3
        if (flight < hit.distance) {
          // A collision: absorbed with probability 1 - albedo (line 15), else scattered
          // (line 16) by the phase function about the travel direction.
          ++count.collisions;
          origin += flight * d;
          t_near = 0.0;
          if (!(u[1] < channel.albedo)) return radiance;
          ++collisions;
          if (order > 0 && collisions > order) return radiance;
          if (collisions > volumetric_roulette_after) {
            if (!(u[2] < roulette_survival)) return radiance;
            weight /= roulette_survival;
          }
          const auto v = random.next4();
          const double cos_theta = channel.phase.sample_cos_theta(v[0]);
          const double phi = 2.0 * pi * v[1];
          d = scatter_direction(d, cos_theta, std::cos(phi), std::sin(phi));
          continue;
        }
        ++count.boundary;
        origin = point_at(hit);
        t_near = tracer_.epsilon();
        if (!cross_boundary(hit, d, inside, u[1])) {
          ++count.lost;
          return radiance;
        }
        after_floor = false;
        continue;
      }
      // Outside: the nearest of the mesh, the floor and the light.
      const double t_mesh = hits_mesh ? hit.distance : infinity;
      double t_floor = infinity;
      if (scene_.floor && d.z() < 0.0) {
        const double t = (scene_.floor->height - origin.z()) / d.z();
        if (t > 0.0) t_floor = t;
      }
      const double t_light = distance_to_light(origin, d, light.position, light.radius);
      if (t_light < t_mesh && t_light < t_floor) {
        // The floor's next-event estimate already holds the light seen straight from it.
        if (after_floor) return radiance;
        if (order > 0 && collisions != order) return radiance;
        ++count.light_hits;
        return radiance + weight * light_radiance_;
      }
      if (t_mesh < t_floor) {
        ++count.boundary;
        origin = point_at(hit);
        t_near = tracer_.epsilon();
        if (!cross_boundary(hit, d, inside, u[1])) {
          ++count.lost;
          return radiance;
        }
        after_floor = false;
        continue;
      }
      if (std::isfinite(t_floor)) {
        origin += t_floor * d;
        origin.z() = scene_.floor->height;
        t_near = 0.0;
        if (order == 0 || collisions == order) {
          radiance += weight * floor_direct(origin, channel.floor_albedo, random, count);
        }
        // The bounce: survival with probability albedo, a cosine-weighted direction (Malley).
        if (!(u[1] < channel.floor_albedo)) return radiance;
        const double r = std::sqrt(u[2]);
        const double phi = 2.0 * pi * u[3];
        d = Vec3(r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0, 1.0 - u[2])));
        after_floor = true;
        continue;
      }
      // Leaves the scene.
      if (order > 0 && collisions != order) return radiance;
      return radiance + weight * scene_.environment_radiance;
    }
  }

  const RenderScene& scene_;
  const RenderSettings& settings_;
  MeshRayTracer tracer_;
  double light_radiance_;
};

}  // namespace

VolumetricResult render_volumetric(const RenderScene& scene, const RenderSettings& settings,
                                   const WorkProgress& progress) {
  if (settings.method != RenderMethod::volumetric) {
    throw std::invalid_argument("render_volumetric: method " + to_string(settings.method));
  }
  if (!(scene.light.radius > 0.0)) {
    throw InputError("light.radius", "0 (a point light) with method volumetric",
                     "a sphere light of radius > 0 (paths reach the light by hitting it)");
  }
  if (settings.scattering_order < 0) {
    throw std::invalid_argument("render_volumetric: negative scattering order");
  }
  check_render_work(scene, settings);
  check_render_memory(scene, settings);
  const auto start = std::chrono::steady_clock::now();
  VolumetricResult result;
  result.image = RgbImage(scene.width, scene.height);
  result.standard_error = RgbImage(scene.width, scene.height);
  VolumetricTracer(scene, settings).render(result, progress);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace scatterlab
