#include "scatterlab/render/volumetric_renderer.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "image_tiles.hpp"
#include "scatterlab/core/constants.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/core/fresnel.hpp"
#include "scatterlab/core/phase_function.hpp"
#include "scatterlab/core/random.hpp"
#include "scatterlab/mesh/mesh_ray_tracer.hpp"

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

// Per-channel values (red, green, blue; only the first `channels` are used).
using Rgb = std::array<double, 3>;

// The media a path sees, one per channel, and the floor's albedo per channel.
struct ChannelMedia {
  int channels = 1;
  Rgb sigma_t{}, sigma_s{}, albedo{}, floor_albedo{};
  std::array<HenyeyGreenstein, 3> phase{HenyeyGreenstein{0.0}, HenyeyGreenstein{0.0},
                                        HenyeyGreenstein{0.0}};
  bool same_phase = true;
};

class VolumetricTracer {
 public:
  VolumetricTracer(const RenderScene& scene, const RenderSettings& settings)
      : scene_(scene),
        settings_(settings),
        tracer_(scene.mesh),
        light_radiance_(scene.light.intensity / (pi * scene.light.radius * scene.light.radius)) {}

  void render(VolumetricResult& result, const WorkProgress& progress) {
    // Three channels for a medium per channel or a coloured floor; otherwise one, shown grey.
    ChannelMedia media;
    const bool grey_floor = !scene_.floor || (scene_.floor->albedo[0] == scene_.floor->albedo[1] &&
                                              scene_.floor->albedo[1] == scene_.floor->albedo[2]);
    media.channels = scene_.channel_media.empty() && grey_floor ? 1 : 3;
    for (std::size_t c = 0; c < static_cast<std::size_t>(media.channels); ++c) {
      const Medium& m = scene_.channel_media.empty() ? scene_.medium : scene_.channel_media[c];
      media.sigma_t[c] = m.sigma_t;
      media.sigma_s[c] = m.sigma_s();
      media.albedo[c] = m.albedo;
      media.phase[c] = HenyeyGreenstein{m.g};
      media.same_phase = media.same_phase && m.g == media.phase[0].g;
      media.floor_albedo[c] = scene_.floor ? scene_.floor->albedo[c] : 0.0;
    }
    const auto pixels = [&](int x0, int x1, int y0, int y1, VolumetricCounters& count) {
      for (int j = y0; j < y1; ++j) {
        for (int i = x0; i < x1; ++i) {
          const Vec3 d = scene_.camera.ray_direction(i, j, scene_.width, scene_.height);
          const auto pixel = static_cast<std::uint64_t>(j) * scene_.width + i;
          Rgb mean{}, error{};
          pixel_value(media, d, pixel, mean, error, count);
          for (std::size_t k = 0; k < 3; ++k) {
            const std::size_t c = media.channels == 1 ? 0 : k;
            result.image.channels[k].at(i, j) = mean[c];
            result.standard_error.channels[k].at(i, j) = error[c];
          }
        }
      }
    };
    for (const auto& c : render_tiles<VolumetricCounters>(scene_.width, scene_.height,
                                                          settings_.threads, progress, pixels)) {
      result.counters.paths += c.paths;
      result.counters.collisions += c.collisions;
      result.counters.boundary += c.boundary;
      result.counters.light_hits += c.light_hits;
      result.counters.shadow_rays += c.shadow_rays;
      result.counters.lost += c.lost;
    }
  }

 private:
  // The mean of `samples` paths from the camera along d, and its standard error, per channel.
  void pixel_value(const ChannelMedia& media, const Vec3& d, std::uint64_t pixel, Rgb& mean,
                   Rgb& error, VolumetricCounters& count) const {
    const int n = scene_.samples;
    Rgb sum{}, sum2{};
    for (int s = 0; s < n; ++s) {
      // (seed, pixel, sample): samples <= 2^20 (render_scene.hpp), pixels <= 2^28.
      PhotonRandom random(settings_.seed, (pixel << 20) | static_cast<std::uint64_t>(s));
      const Rgb f = trace(media, scene_.camera.position, d, random, count);
      for (std::size_t c = 0; c < 3; ++c) {
        sum[c] += f[c];
        sum2[c] += f[c] * f[c];
      }
    }
    for (std::size_t c = 0; c < 3; ++c) {
      mean[c] = sum[c] / n;
      const double variance =
          n > 1 ? std::max(0.0, sum2[c] / n - mean[c] * mean[c]) / (n - 1) : 0.0;
      error[c] = std::sqrt(variance);
    }
  }

  Vec3 point_at(const MeshHit& hit) const {
    const TriangleMesh& mesh = scene_.mesh;
    return (1.0 - hit.bary_a - hit.bary_b) * mesh.vertex(hit.triangle, 0) +
           hit.bary_a * mesh.vertex(hit.triangle, 1) + hit.bary_b * mesh.vertex(hit.triangle, 2);
  }

  // Reflection or refraction at the mesh, chosen with the Fresnel reflectance (Bitterli
  // Algorithm 1, lines 6-10, from either side). `inside` flips on refraction. The facet's own
  // normal decides, never an interpolated one, as simulate's mesh transport does
  // (mesh/mesh_boundary.hpp): a shading normal can send a reflected path through the facet or
  // a refracted one back, which loses the path (0.02 % of the milk sphere's paths did) and breaks
  // energy conservation. So a mesh's shading normals change nothing in this method; a ray meets
  // the facet from the side `inside` says, and the new direction lies on the side it chose.
  // False only where rounding disagrees (a ray grazing the facet).
  bool cross_boundary(const MeshHit& hit, Vec3& d, bool& inside, double xi) const {
    const Vec3 n = scene_.mesh.geometric_normal(hit.triangle);  // outward
    const Vec3 facing = inside ? Vec3(-n) : n;  // towards the side the ray comes from
    const double eta = inside ? 1.0 / scene_.eta : scene_.eta;  // n_transmitted / n_incident
    const double cos_i = -d.dot(facing);
    if (!(cos_i > 0.0)) return false;  // met the facet from the side it should not have
    const FresnelDielectric terms = fresnel_dielectric_terms(cos_i, eta);
    Vec3 next;
    bool crossed = false;
    if (xi < terms.reflectance() || terms.total_internal_reflection) {
      next = d + 2.0 * cos_i * facing;  // mirror reflection (also total internal reflection)
    } else {
      next = refracted(d, facing, eta, cos_i, terms.cos_transmitted);
      crossed = true;
    }
    const bool goes_out = next.dot(n) > 0.0;
    const bool now_inside = crossed ? !inside : inside;
    if (goes_out == now_inside) return false;
    d = next;
    inside = now_inside;
    return true;
  }

  // Next-event estimate of the light's direct radiance off the floor point x, per unit of the
  // path's weight and of the albedo a: uniform in the cone of the sphere light (pbrt-v4
  // §12.2.3), so that L_d / a ~ (1 / pi) L_e cos theta / pdf = 2 L_e cos theta (1 - cos theta_max),
  // and 0 when the object blocks the shadow ray.
  double floor_direct(const Vec3& x, PhotonRandom& random, VolumetricCounters& count) const {
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
    return 2.0 * light_radiance_ * cos_floor * one_minus_cos_max;
  }

  // Russian roulette on the largest channel weight m < 1: survive with probability m and
  // divide by it (unbiased; with one channel this is analog absorption, Algorithm 1 line 15).
  static bool survives(Rgb& weight, int channels, double xi) {
    const double m = *std::max_element(weight.begin(), weight.begin() + channels);
    if (m >= 1.0) return true;
    if (!(xi < m)) return false;
    for (double& w : weight) w /= m;
    return true;
  }

  // One path from `origin` along `d`: the radiance it carries back per channel, times its
  // weights. All channels follow one path, sampled with the media of one "hero" channel h
  // chosen at random (Wilkie et al. 2014, "Hero wavelength spectral sampling", §4): free
  // flights from exp(-sigma_t,h t), directions from HG with g_h. Channel c's weight is the
  // balance heuristic over the N channels' strategies for the whole path,
  //   w_c = f_c / ((1/N) sum_k p_k) = A_c / ((1/N) sum_k p_k / p_c),
  // with p_k the path's density when sampled with channel k (its collision densities
  // sigma_t,k exp(-sigma_t,k t), boundary transmittances exp(-sigma_t,k t_b) and phase values;
  // Fresnel choices and the floor's cosine are the same for every channel and cancel) and
  // A_c = f_c / p_c the product of channel c's albedos (and floor albedos) along the path.
  // Since p_c <= sum_k p_k, w_c <= N A_c: the weights stay bounded however long the path.
  // Absorption is a roulette on the largest A_c (with one channel: Algorithm 1's analog
  // absorption, and w = 1).
  Rgb trace(const ChannelMedia& media, Vec3 origin, Vec3 d, PhotonRandom& random,
            VolumetricCounters& count) const {
    ++count.paths;
    const RenderLight& light = scene_.light;
    const int order = settings_.scattering_order;
    const int n = media.channels;
    const auto nc = static_cast<std::size_t>(n);
    const auto start = random.next4();
    const auto hero = std::min(static_cast<std::size_t>(start[0] * n), nc - 1);
    Rgb albedos{1.0, 1.0, 1.0};  // A_c, times the roulettes' 1 / q
    Rgb log_pdf{};               // log p_c of the path so far (one channel: unused)
    Rgb radiance{};
    double t_near = 0.0;
    bool inside = false;
    bool after_floor = false;  // nothing but the floor's bounce since the last floor point
    int collisions = 0;
    // Adds value_c times the path's weight w_c for each channel.
    const auto add = [&](const Rgb& value) {
      for (std::size_t c = 0; c < nc; ++c) {
        double ratio_sum = 0.0;  // sum_k p_k / p_c
        for (std::size_t k = 0; k < nc; ++k) ratio_sum += std::exp(log_pdf[k] - log_pdf[c]);
        radiance[c] += value[c] * albedos[c] * n / ratio_sum;
      }
    };
    const auto grey = [](double v) { return Rgb{v, v, v}; };
    // Reflected or refracted where the path meets the mesh; false when it is lost there.
    const auto meet_boundary = [&](const MeshHit& hit, double xi) {
      ++count.boundary;
      origin = point_at(hit);
      t_near = tracer_.epsilon();
      if (!cross_boundary(hit, d, inside, xi)) {
        ++count.lost;
        return false;
      }
      after_floor = false;
      return true;
    };
    // Every branch ends the path or moves it on; a path lives until it leaves, is absorbed or
    // loses a roulette.
    for (;;) {
      const auto u = random.next4();
      MeshHit hit;
      const bool hits_mesh = tracer_.intersect(origin, d, t_near, infinity, hit);
      if (inside) {
        if (!hits_mesh) {  // rounding let the path slip through the mesh
          ++count.lost;
          return radiance;
        }
        const double flight = -std::log(u[0]) / media.sigma_t[hero];  // Algorithm 1, line 3
        if (flight < hit.distance) {
          // A collision: each channel's density sigma_t,c exp(-sigma_t,c t) and albedo.
          ++count.collisions;
          origin += flight * d;
          t_near = 0.0;
          for (std::size_t c = 0; c < nc; ++c) {
            if (n > 1) log_pdf[c] += std::log(media.sigma_t[c]) - media.sigma_t[c] * flight;
            albedos[c] *= media.albedo[c];
          }
          if (!survives(albedos, n, u[1])) return radiance;  // absorbed (line 15)
          ++collisions;
          if (order > 0 && collisions > order) return radiance;
          const auto v = random.next4();
          if (collisions > volumetric_roulette_after) {
            if (!(v[3] < roulette_survival)) return radiance;
            for (double& a : albedos) a /= roulette_survival;
          }
          // A new direction (line 16) from the hero's phase function.
          const double cos_theta = media.phase[hero].sample_cos_theta(v[0]);
          const double phi = 2.0 * pi * v[1];
          d = scatter_direction(d, cos_theta, std::cos(phi), std::sin(phi));
          if (!media.same_phase) {
            for (std::size_t c = 0; c < nc; ++c) {
              log_pdf[c] += std::log(media.phase[c].evaluate(cos_theta));
            }
          }
          continue;
        }
        // The boundary: each channel's transmittance exp(-sigma_t,c t_b).
        if (n > 1) {
          for (std::size_t c = 0; c < nc; ++c) log_pdf[c] -= media.sigma_t[c] * hit.distance;
        }
        if (!meet_boundary(hit, u[1])) return radiance;
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
        add(grey(light_radiance_));
        return radiance;
      }
      if (t_mesh < t_floor) {
        if (!meet_boundary(hit, u[1])) return radiance;
        continue;
      }
      if (std::isfinite(t_floor)) {
        origin += t_floor * d;
        origin.z() = scene_.floor->height;
        t_near = 0.0;
        if (order == 0 || collisions == order) {
          const double direct = floor_direct(origin, random, count);
          if (direct > 0.0) {
            Rgb value{};
            for (std::size_t c = 0; c < nc; ++c) value[c] = media.floor_albedo[c] * direct;
            add(value);
          }
        }
        // The bounce: the albedo joins A_c, then the roulette; a cosine-weighted direction
        // (Malley's method), whose pdf cos / pi cancels the BRDF's cos / pi.
        for (std::size_t c = 0; c < nc; ++c) albedos[c] *= media.floor_albedo[c];
        if (!survives(albedos, n, u[1])) return radiance;
        const double r = std::sqrt(u[2]);
        const double phi = 2.0 * pi * u[3];
        d = Vec3(r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0, 1.0 - u[2])));
        after_floor = true;
        continue;
      }
      // Leaves the scene.
      if (order > 0 && collisions != order) return radiance;
      add(grey(scene_.environment_radiance));
      return radiance;
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
