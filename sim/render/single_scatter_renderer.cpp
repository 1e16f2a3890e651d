#include "scatterlab/render/single_scatter_renderer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "image_tiles.hpp"
#include "scatterlab/core/constants.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/core/fresnel.hpp"
#include "scatterlab/core/phase_function.hpp"
#include "scatterlab/core/random.hpp"
#include "scatterlab/mesh/mesh_ray_tracer.hpp"
#include "scatterlab/refract/path_contribution.hpp"
#include "scatterlab/refract/refractive_solver.hpp"
#include "scatterlab/refract/support_interval.hpp"

namespace scatterlab {

RenderMethod parse_render_method(const std::string& name) {
  if (name == "straight") return RenderMethod::straight;
  if (name == "walter") return RenderMethod::walter;
  if (name == "holzschuch") return RenderMethod::holzschuch;
  if (name == "pathtrace") return RenderMethod::pathtrace;
  if (name == "volumetric") return RenderMethod::volumetric;
  if (name == "bssrdf") return RenderMethod::bssrdf;
  throw InputError(
      "method", "got \"" + name + "\"",
      "\"straight\", \"walter\", \"holzschuch\", \"pathtrace\", \"volumetric\" or \"bssrdf\"");
}

std::string to_string(RenderMethod method) {
  switch (method) {
    case RenderMethod::straight:
      return "straight";
    case RenderMethod::walter:
      return "walter";
    case RenderMethod::holzschuch:
      return "holzschuch";
    case RenderMethod::pathtrace:
      return "pathtrace";
    case RenderMethod::volumetric:
      return "volumetric";
    case RenderMethod::bssrdf:
      return "bssrdf";
  }
  return "?";
}

// Points standing for the light (see the header): a point light is itself; a sphere light is
// the disc it shows the object, centred on the light and facing `target`, cut into M cells of
// equal area (Vogel's spiral: radius r sqrt((k + 1/2) / M), golden-angle turns), each an
// isotropic point of intensity I / M.
std::vector<LightPoint> light_points(const RenderLight& light, int count, const Vec3& target) {
  if (light.radius == 0.0) return {{light.position, light.intensity}};
  const Frame frame(Vec3(target - light.position).normalized());
  const double golden = pi * (3.0 - std::sqrt(5.0));
  std::vector<LightPoint> points;
  for (int k = 0; k < count; ++k) {
    const double r = light.radius * std::sqrt((k + 0.5) / count);
    const double phi = golden * k;
    const Vec3 offset = std::cos(phi) * frame.tangent + std::sin(phi) * frame.bitangent;
    points.push_back({light.position + r * offset, light.intensity / count});
  }
  return points;
}

namespace {

// Distances along [a, b] with density proportional to exp(-sigma_t x): x(u) inverts the CDF.
struct TransmittanceSampler {
  double a, sigma_t, mass;  // mass = int_a^b exp(-sigma_t x) dx
  double span_factor;       // 1 - exp(-sigma_t (b - a))

  TransmittanceSampler(double a_, double b, double sigma_t_) : a(a_), sigma_t(sigma_t_) {
    span_factor = -std::expm1(-sigma_t * (b - a));
    mass = std::exp(-sigma_t * a) * span_factor / sigma_t;
  }
  double at(double u) const { return a - std::log1p(-u * span_factor) / sigma_t; }
};

struct EyeSegmentInside {
  EyeSegment segment;
  double weight = 0.0;  // T_0 / eta^2
};

class Renderer {
 public:
  Renderer(const RenderScene& scene, const RenderSettings& settings)
      : scene_(scene),
        settings_(settings),
        tracer_(scene.mesh),
        solver_(scene.mesh, scene.eta),
        phase_{scene.medium.g},
        lights_(light_points(scene.light, scene.light_samples, scene.mesh.bounds().center())) {
    if (settings.method == RenderMethod::holzschuch) {
      lit_.reserve(lights_.size());
      for (const LightPoint& light : lights_)
        lit_.emplace_back(solver_, Light::point(light.position));
    }
  }

  // Compile-time specialised once per run: refraction at the boundary, and shading normals.
  template <bool Refracting, bool Smooth>
  void render(RenderResult& result, const WorkProgress& progress) {
    const auto pixels = [&](int x0, int x1, int y0, int y1, RenderCounters& count) {
      std::vector<RefractionPath> paths;
      std::vector<TriangleSupport> supports;
      for (int j = y0; j < y1; ++j) {
        for (int i = x0; i < x1; ++i) {
          EyeSegmentInside eye;
          if (!enter<Refracting, Smooth>(i, j, eye)) continue;
          ++count.eye_rays;
          double value = 0.0, error = 0.0;
          switch (settings_.method) {
            case RenderMethod::straight:
              value = straight<Smooth>(eye.segment, count);
              break;
            case RenderMethod::walter:
              value = walter(eye.segment, paths, count);
              break;
            case RenderMethod::holzschuch:
              value = settings_.shared_points
                          ? holzschuch_shared(eye.segment, paths, supports, count)
                          : holzschuch(eye.segment, paths, supports, count);
              break;
            case RenderMethod::pathtrace:
              value = pathtrace<Smooth>(
                  eye.segment, static_cast<std::uint64_t>(j) * scene_.width + i, error, count);
              break;
            case RenderMethod::volumetric:  // refused by render_single_scatter
            case RenderMethod::bssrdf:
              break;
          }
          result.image.at(i, j) = eye.weight * value;
          result.standard_error.at(i, j) = eye.weight * error;
        }
      }
    };
    for (const auto& c : render_tiles<RenderCounters>(scene_.width, scene_.height,
                                                      settings_.threads, progress, pixels)) {
      result.counters.eye_rays += c.eye_rays;
      result.counters.point_queries += c.point_queries;
      result.counters.triangle_searches += c.triangle_searches;
      result.counters.paths += c.paths;
      result.counters.supports += c.supports;
      result.counters.blocked_paths += c.blocked_paths;
    }
  }

 private:
  template <bool Smooth>
  Vec3 normal_at(const MeshHit& hit) const {
    const TriangleMesh& mesh = scene_.mesh;
    if constexpr (Smooth) {
      const double w0 = 1.0 - hit.bary_a - hit.bary_b;
      return (w0 * mesh.corner_normal(hit.triangle, 0) +
              hit.bary_a * mesh.corner_normal(hit.triangle, 1) +
              hit.bary_b * mesh.corner_normal(hit.triangle, 2))
          .normalized();
    } else {
      return mesh.geometric_normal(hit.triangle);
    }
  }

  Vec3 point_at(const MeshHit& hit) const {
    const TriangleMesh& mesh = scene_.mesh;
    return (1.0 - hit.bary_a - hit.bary_b) * mesh.vertex(hit.triangle, 0) +
           hit.bary_a * mesh.vertex(hit.triangle, 1) + hit.bary_b * mesh.vertex(hit.triangle, 2);
  }

  // The eye ray's first hit, Fresnel transmission and refraction into the medium, and the exit.
  template <bool Refracting, bool Smooth>
  bool enter(int i, int j, EyeSegmentInside& eye) const {
    const Vec3 origin = scene_.camera.position;
    const Vec3 d = scene_.camera.ray_direction(i, j, scene_.width, scene_.height);
    MeshHit hit;
    if (!tracer_.intersect(origin, d, 0.0, 1e300, hit)) return false;
    const Vec3 p0 = point_at(hit);
    const Vec3 n = normal_at<Smooth>(hit);
    const double cos_i = -d.dot(n);
    if (!(cos_i > 0.0)) return false;
    Vec3 inside = d;
    double weight = 1.0;
    if constexpr (Refracting) {
      // Fresnel (core/fresnel.hpp) and Snell from outside (index 1) into the medium (eta); the
      // radiance leaving the medium towards the camera is T L / eta^2 (n^2 law).
      const FresnelDielectric terms = fresnel_dielectric_terms(cos_i, scene_.eta);
      if (terms.total_internal_reflection) return false;
      inside = refracted(d, n, scene_.eta, cos_i, terms.cos_transmitted);
      weight = (1.0 - terms.reflectance()) / (scene_.eta * scene_.eta);
    }
    if (!(inside.dot(scene_.mesh.geometric_normal(hit.triangle)) < 0.0)) return false;
    MeshHit exit;
    if (!tracer_.intersect(p0, inside, tracer_.epsilon(), 1e300, exit)) return false;
    eye.segment = EyeSegment{p0, inside, 0.0, exit.distance};
    eye.weight = weight;
    return true;
  }

  // Whether light can take the refracted path: nothing of the boundary between V and P (the leg
  // inside) or between P and the light (the leg outside). The solver finds every path that obeys
  // Snell's law at one triangle; on a shape that is not convex, another part of the boundary can
  // lie across either leg (Walter et al. 2009, §5 tests both with shadow rays).
  // Each leg starts a little off P along the facet's normal, to its own side: started on the
  // surface, a leg that grazes a flat face would meet its coplanar neighbours in single precision.
  // A leg shorter than twice that offset is not tested: nothing can be resolved across it.
  bool unblocked(const RefractionPath& path) const {
    const double epsilon = tracer_.epsilon();
    const Vec3 off = epsilon * scene_.mesh.geometric_normal(path.triangle);
    const auto open = [&](const Vec3& from, const Vec3& direction, double length) {
      return length <= 2.0 * epsilon || !tracer_.occluded(from, direction, 0.0, length - epsilon);
    };
    return open(path.point - off, path.omega_v, path.distance_v) &&
           open(path.point + off, path.omega_l, std::min(path.distance_l, 1e30));
  }

  // S(V) of the header over the paths in `paths` that light can take, for one light point.
  double path_sum(const EyeSegment& segment, const LightPoint& light,
                  const std::vector<RefractionPath>& paths, RenderCounters& count) const {
    double sum = 0.0;
    for (const RefractionPath& path : paths) {
      if (!unblocked(path)) {
        ++count.blocked_paths;
        continue;
      }
      const PathContribution c = path_contribution(solver_.triangle(path.triangle), path,
                                                   scene_.eta, scene_.medium.sigma_t, false);
      // Light travels along omega_v at V and leaves towards the camera along -direction.
      const double cos_theta = -path.omega_v.dot(segment.direction);
      sum += phase_.evaluate(cos_theta) * light.intensity * c.irradiance;
    }
    return sum;
  }

  double walter(const EyeSegment& segment, std::vector<RefractionPath>& paths,
                RenderCounters& count) const {
    const TransmittanceSampler sampler(segment.t0, segment.t1, scene_.medium.sigma_t);
    const int n = scene_.samples;
    double sum = 0.0;
    RefractionStats stats;
    for (int s = 0; s < n; ++s) {
      const Vec3 v = segment.at(sampler.at((s + 0.5) / n));
      for (const LightPoint& light : lights_) {
        paths.clear();
        solver_.find_paths(v, Light::point(light.position), paths, stats);
        sum += path_sum(segment, light, paths, count);
      }
    }
    count.point_queries += stats.queries;
    count.triangle_searches += stats.triangles_tested;
    count.paths += stats.paths;
    return scene_.medium.sigma_s() * sampler.mass * sum / n;
  }

  double holzschuch(const EyeSegment& segment, std::vector<RefractionPath>& paths,
                    std::vector<TriangleSupport>& supports, RenderCounters& count) const {
    double sum = 0.0;
    RefractionStats stats;
    SupportStats support_stats;
    const int n = scene_.samples;
    for (std::size_t k = 0; k < lights_.size(); ++k) {
      const LightPoint& light = lights_[k];
      const Light& point = lit_[k].light();
      supports.clear();
      find_segment_supports(lit_[k], segment, supports, support_stats);
      count.point_queries += supports.size() * static_cast<std::size_t>(n);
      for (const TriangleSupport& support : supports) {
        const TransmittanceSampler sampler(support.interval.x_min, support.interval.x_max,
                                           scene_.medium.sigma_t);
        double triangle_sum = 0.0;
        for (int s = 0; s < n; ++s) {
          const Vec3 v = segment.at(sampler.at((s + 0.5) / n));
          paths.clear();
          solver_.find_paths_through(support.triangle, v, point, paths, stats);
          solver_.merge_duplicates(paths, 0, stats);
          triangle_sum += path_sum(segment, light, paths, count);
        }
        sum += sampler.mass * triangle_sum / n;
      }
    }
    count.supports += support_stats.supports;
    count.triangle_searches += stats.triangles_tested;
    count.paths += stats.paths;
    return scene_.medium.sigma_s() * sum;
  }

  double holzschuch_shared(const EyeSegment& segment, std::vector<RefractionPath>& paths,
                           std::vector<TriangleSupport>& supports, RenderCounters& count) const {
    const TransmittanceSampler sampler(segment.t0, segment.t1, scene_.medium.sigma_t);
    const int n = scene_.samples;
    double sum = 0.0;
    RefractionStats stats;
    SupportStats support_stats;
    for (std::size_t k = 0; k < lights_.size(); ++k) {
      const LightPoint& light = lights_[k];
      const Light& point = lit_[k].light();
      supports.clear();
      find_segment_supports(lit_[k], segment, supports, support_stats);
      count.point_queries += static_cast<std::size_t>(n);
      for (int s = 0; s < n; ++s) {
        const double x = sampler.at((s + 0.5) / n);
        const Vec3 v = segment.at(x);
        paths.clear();
        for (const TriangleSupport& support : supports) {
          if (support.interval.contains(x)) {
            solver_.find_paths_through(support.triangle, v, point, paths, stats);
          }
        }
        solver_.merge_duplicates(paths, 0, stats);
        sum += path_sum(segment, light, paths, count);
      }
    }
    count.supports += support_stats.supports;
    count.triangle_searches += stats.triangles_tested;
    count.paths += stats.paths;
    return scene_.medium.sigma_s() * sampler.mass * sum / n;
  }

  // Jensen et al. 2001, §4.3: the shadow ray runs straight from V to the light point, meeting
  // the boundary at x_i after the observed distance s_i at cosine mu = w . n_i, and the light's
  // refraction there is accounted for by two corrections (Bitterli 2013, §2.6.2 describes them):
  // the attenuation takes the refracted distance s_i' = s_i mu / sqrt(1 - (1 - mu^2) / eta^2),
  // and the phase function the refracted direction omega_i'. The distance is exact for a flat
  // boundary seen along the straight ray: V lies s_i mu below the tangent plane at x_i, and light
  // refracted there crosses that depth at cosine mu_t = sqrt(1 - (1 - mu^2) / eta^2), in s_i mu /
  // mu_t.
  template <bool Smooth>
  double straight(const EyeSegment& segment, RenderCounters& count) const {
    const TransmittanceSampler sampler(segment.t0, segment.t1, scene_.medium.sigma_t);
    const int n = scene_.samples;
    double sum = 0.0;
    for (int s = 0; s < n; ++s) {
      const Vec3 v = segment.at(sampler.at((s + 0.5) / n));
      for (const LightPoint& light : lights_) {
        ++count.point_queries;
        const Vec3 to_light = light.position - v;
        const double distance = to_light.norm();
        const Vec3 w = to_light / distance;
        MeshHit hit;
        if (!tracer_.intersect(v, w, 0.0, distance, hit)) continue;
        const Vec3 n_s = normal_at<Smooth>(hit);
        const double cos_l = w.dot(n_s);
        if (!(cos_l > 0.0)) continue;
        if (tracer_.occluded(v, w, hit.distance + tracer_.epsilon(), distance)) continue;
        // omega_i', the light's direction inside, and the Fresnel terms of its crossing.
        const FresnelDielectric terms = fresnel_dielectric_terms(cos_l, scene_.eta);
        if (terms.total_internal_reflection) continue;
        const Vec3 inside =
            scene_.eta != 1.0 ? refracted(-w, n_s, scene_.eta, cos_l, terms.cos_transmitted) : -w;
        ++count.paths;
        const double cos_t = -inside.dot(n_s);
        const double transmittance = 1.0 - terms.reflectance();
        const double refracted_distance = hit.distance * cos_l / cos_t;
        const double irradiance = transmittance *
                                  std::exp(-scene_.medium.sigma_t * refracted_distance) /
                                  (distance * distance);
        // The light travels along omega_i' and leaves towards the camera along -direction.
        sum += phase_.evaluate(-inside.dot(segment.direction)) * light.intensity * irradiance;
      }
    }
    return scene_.medium.sigma_s() * sampler.mass * sum / n;
  }

  // Monte Carlo single scattering with the sphere light; returns the mean and sets its standard
  // error.
  template <bool Smooth>
  double pathtrace(const EyeSegment& segment, std::uint64_t pixel, double& error,
                   RenderCounters& count) const {
    const TransmittanceSampler sampler(segment.t0, segment.t1, scene_.medium.sigma_t);
    const RenderLight& light = scene_.light;
    const double radiance = light.intensity / (pi * light.radius * light.radius);
    const double eta = scene_.eta;
    PhotonRandom random(settings_.seed, pixel);
    const int n = scene_.samples;
    double sum = 0.0, sum2 = 0.0;
    for (int s = 0; s < n; ++s) {
      const auto u = random.next4();
      const Vec3 v = segment.at(sampler.at((s + u[0]) / n));  // stratified in the CDF
      // Backwards from V: the phase function about the eye ray's direction (cos theta between
      // the light's travel -w and the camera-bound -direction is w . direction).
      const double cos_theta = phase_.sample_cos_theta(u[1]);
      const double phi = 2.0 * pi * u[2];
      const Vec3 w = scatter_direction(segment.direction, cos_theta, std::cos(phi), std::sin(phi));
      ++count.point_queries;
      MeshHit hit;
      if (!tracer_.intersect(v, w, 0.0, 1e300, hit)) continue;
      const Vec3 n_s = normal_at<Smooth>(hit);
      const double cos_o = w.dot(n_s);
      if (!(cos_o > 0.0)) continue;
      Vec3 out = w;
      double transmittance = 1.0;
      if (eta != 1.0) {
        const FresnelDielectric terms = fresnel_dielectric_terms(cos_o, 1.0 / eta);
        if (terms.total_internal_reflection) continue;
        out = refracted(w, -n_s, 1.0 / eta, cos_o, terms.cos_transmitted);
        transmittance = 1.0 - terms.reflectance();
      }
      const Vec3 p = point_at(hit);
      if (!(out.dot(scene_.mesh.geometric_normal(hit.triangle)) > 0.0)) continue;
      // The sphere light along out from p, unless the mesh comes first.
      const Vec3 oc = p - light.position;
      const double b = oc.dot(out);
      const double disc = b * b - (oc.squaredNorm() - light.radius * light.radius);
      if (disc < 0.0) continue;
      const double t_light = -b - std::sqrt(disc);
      if (!(t_light > 0.0)) continue;
      if (tracer_.occluded(p, out, tracer_.epsilon(), t_light)) continue;
      ++count.paths;
      // Radiance inside: T eta^2 L_e (n^2 law); phase sampling cancels p / pdf.
      const double f =
          transmittance * eta * eta * radiance * std::exp(-scene_.medium.sigma_t * hit.distance);
      sum += f;
      sum2 += f * f;
    }
    const double mean = sum / n;
    const double variance = n > 1 ? std::max(0.0, (sum2 / n - mean * mean)) / (n - 1) : 0.0;
    const double scale = scene_.medium.sigma_s() * sampler.mass;
    error = scale * std::sqrt(variance);
    return scale * mean;
  }

  const RenderScene& scene_;
  const RenderSettings& settings_;
  MeshRayTracer tracer_;
  RefractiveSolver solver_;
  HenyeyGreenstein phase_;
  std::vector<LightPoint> lights_;
  std::vector<RefractedLight> lit_;  // holzschuch: per light point
};

}  // namespace

MemoryEstimate render_memory(const RenderScene& scene, const RenderSettings& settings) {
  const auto pixels =
      static_cast<std::uint64_t>(scene.width) * static_cast<std::uint64_t>(scene.height);
  const auto lights =
      static_cast<std::uint64_t>(scene.light.radius == 0.0 ? 1 : scene.light_samples);
  MemoryEstimate need;
  // The image and its standard error, and the PNG's and OpenEXR's copies when written; three
  // channels of each for volumetric.
  need.add_doubles(fmt::format("images of {} x {} pixels", scene.width, scene.height), pixels,
                   settings.method == RenderMethod::volumetric ? 12 : 4);
  need.add(fmt::format("{} light points", lights), saturating_product(lights, sizeof(LightPoint)));
  if (settings.method == RenderMethod::holzschuch) {
    const std::size_t triangles = scene.mesh.triangle_count();
    // The position-normal tree has fewer nodes than twice the triangles.
    const std::uint64_t per_light = RefractedLight::table_bytes(triangles, 2 * triangles);
    need.add(fmt::format("{} light tables of {} triangles", lights, triangles),
             saturating_product(lights, per_light));
  }
  return need;
}

void check_render_memory(const RenderScene& scene, const RenderSettings& settings) {
  check_memory(render_memory(scene, settings),
               "image.width x image.height, image.light_samples, mesh triangles",
               "a smaller image, fewer light samples or a coarser mesh");
}

namespace {

// Points on the light per sample: one for the Monte Carlo methods, which find the light by
// sampling (volumetric: one path carries every channel).
std::uint64_t light_factor(const RenderScene& scene, const RenderSettings& settings) {
  const bool monte_carlo =
      settings.method == RenderMethod::pathtrace || settings.method == RenderMethod::volumetric;
  return monte_carlo ? 1 : static_cast<std::uint64_t>(scene.light_samples);
}

}  // namespace

std::uint64_t render_evaluations(const RenderScene& scene, const RenderSettings& settings) {
  const std::uint64_t lights = light_factor(scene, settings);
  return saturating_product(saturating_product(static_cast<std::uint64_t>(scene.width) *
                                                   static_cast<std::uint64_t>(scene.height),
                                               static_cast<std::uint64_t>(scene.samples)),
                            lights);
}

void check_render_work(const RenderScene& scene, const RenderSettings& settings) {
  const std::uint64_t evaluations = render_evaluations(scene, settings);
  if (evaluations <= max_render_evaluations) return;
  // The Monte Carlo methods' light factor is 1, set by no key.
  const bool monte_carlo =
      settings.method == RenderMethod::pathtrace || settings.method == RenderMethod::volumetric;
  throw InputError(
      monte_carlo ? "image.width x image.height x image.samples"
                  : "image.width x image.height x image.samples x image.light_samples",
      fmt::format("{} x {} x {} x {} = {:.3g} light evaluations (months on one core)", scene.width,
                  scene.height, scene.samples, light_factor(scene, settings),
                  static_cast<double>(evaluations)),
      fmt::format("at most 2^42 = {:.3g}: a smaller image, fewer samples or fewer light samples",
                  static_cast<double>(max_render_evaluations)));
}

RenderResult render_single_scatter(const RenderScene& scene, const RenderSettings& settings,
                                   const WorkProgress& progress) {
  if (settings.method == RenderMethod::volumetric || settings.method == RenderMethod::bssrdf) {
    throw std::invalid_argument("render_single_scatter: " + to_string(settings.method) +
                                " is render_volumetric's or render_bssrdf's");
  }
  // What the single-scatter methods do not model is refused, not silently left out.
  if (!scene.channel_media.empty()) {
    throw InputError("medium", "a medium per channel with method " + to_string(settings.method),
                     "one medium (numbers, not [red, green, blue]), or method volumetric");
  }
  refuse_volumetric_only(scene, to_string(settings.method));
  if (settings.method == RenderMethod::pathtrace && !(scene.light.radius > 0.0)) {
    throw InputError("light.radius", "0 (a point light) with method pathtrace",
                     "a sphere light of radius > 0 for the path-traced reference");
  }
  check_render_work(scene, settings);
  check_render_memory(scene, settings);
  const auto start = std::chrono::steady_clock::now();
  RenderResult result;
  result.image = Image(scene.width, scene.height);
  result.standard_error = Image(scene.width, scene.height);
  Renderer renderer(scene, settings);
  const bool refracting = settings.force_general || scene.eta != 1.0;
  const bool smooth = settings.force_general || scene.mesh.has_shading_normals();
  if (refracting && smooth) renderer.render<true, true>(result, progress);
  if (refracting && !smooth) renderer.render<true, false>(result, progress);
  if (!refracting && smooth) renderer.render<false, true>(result, progress);
  if (!refracting && !smooth) renderer.render<false, false>(result, progress);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace scatterlab
