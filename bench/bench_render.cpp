// Single-scatter images of the bumpy sphere (Walter et al. 2009, §5; Holzschuch 2013, Fig. 1):
// time per image of each method at equal samples per eye ray, and time against the mesh's
// triangle count (10^3 to 3 10^5). One thread, small images, a point light, so that the numbers
// are per eye ray costs of the methods themselves, except straight's: its images here are mostly
// its set-up (the Embree and position-normal trees, about 10 ms); beyond it, it costs about 2 us
// per eye ray (measured on 64 x 64, 128 x 128 and 256 x 256 images). Holzschuch 2013 reports its
// method about 230x slower than straight.

#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <filesystem>
#include <map>
#include <memory>

#include "scatterlab/render/render_scene.hpp"
#include "scatterlab/render/single_scatter_renderer.hpp"
#include "scatterlab/render/volumetric_renderer.hpp"

namespace scatterlab {
namespace {

// data/scenes/bumpy-sphere.toml with a point light and `rings` x `segments` vertices
// (2 segments (rings - 1) triangles).
const RenderScene& bumpy_sphere_scene(int rings, int segments) {
  static std::map<std::pair<int, int>, std::unique_ptr<RenderScene>> cache;
  auto& slot = cache[{rings, segments}];
  if (!slot) {
    const std::string toml = fmt::format(
        "[mesh]\nshape = \"bumpy_sphere\"\nradius = 1.0\namplitude = 0.08\nfrequency = 6\n"
        "rings = {}\nsegments = {}\nnormals = \"interpolated\"\n"
        "[medium]\nsigma_s = 0.3\nsigma_a = 0.02\ng = 0.0\neta = 1.5\n"
        "[light]\nposition = [0.0, 4.0, 0.5]\nintensity = 1.0\nradius = 0.0\n"
        "[camera]\nposition = [0.0, -4.0, 0.0]\nlook_at = [0.0, 0.0, 0.0]\n"
        "up = [0.0, 0.0, 1.0]\nfov = 32.0\n"
        "[image]\nwidth = 8\nheight = 8\nsamples = 4\nlight_samples = 1\n",
        rings, segments);
    slot = std::make_unique<RenderScene>(parse_render_scene(toml, "bench"));
  }
  return *slot;
}

void run_image(benchmark::State& state, RenderScene scene, RenderMethod method) {
  RenderSettings settings;
  settings.method = method;
  settings.threads = 1;
  RenderCounters counters;
  for (auto _ : state) {
    const RenderResult result = render_single_scatter(scene, settings);
    counters = result.counters;
    benchmark::DoNotOptimize(result.image.values.data());
  }
  state.counters["triangles"] = static_cast<double>(scene.mesh.triangle_count());
  state.counters["eye_rays"] = static_cast<double>(counters.eye_rays);
  state.counters["paths"] = static_cast<double>(counters.paths);
  // Seconds per eye ray that entered the object (printed with its unit, e.g. 40ms).
  state.counters["per_eye_ray"] = benchmark::Counter(
      static_cast<double>(counters.eye_rays),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

// range(0): method (0 straight, 1 walter, 2 holzschuch); range(1): samples per eye ray.
// 16 x 16 pixels of the 10 080-triangle bumpy sphere.
void BM_RenderMethod(benchmark::State& state) {
  RenderScene scene = bumpy_sphere_scene(71, 72);
  scene.width = scene.height = 16;
  scene.samples = static_cast<int>(state.range(1));
  constexpr RenderMethod methods[] = {RenderMethod::straight, RenderMethod::walter,
                                      RenderMethod::holzschuch};
  state.SetLabel(to_string(methods[state.range(0)]));
  run_image(state, scene, methods[state.range(0)]);
}
BENCHMARK(BM_RenderMethod)
    ->ArgsProduct({{0, 1, 2}, {4, 16}})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

// range(0): method (0 straight, 2 holzschuch); range(1): rings (segments = rings + 1).
// 8 x 8 pixels, 4 samples per eye ray: ~10^3, 10^4, 10^5, 3 10^5 triangles.
void BM_RenderTriangles(benchmark::State& state) {
  const int rings = static_cast<int>(state.range(1));
  const RenderScene& scene = bumpy_sphere_scene(rings, rings + 1);
  const RenderMethod method =
      state.range(0) == 0 ? RenderMethod::straight : RenderMethod::holzschuch;
  state.SetLabel(to_string(method));
  run_image(state, scene, method);
}
BENCHMARK(BM_RenderTriangles)
    ->ArgsProduct({{0, 2}, {23, 71, 224, 388}})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

// Volumetric path tracing of data/scenes/milk-sphere.toml (every order, the floor, three
// channels on each path) at 32 x 24 pixels and 16 paths per pixel, one thread: paths per second.
void BM_RenderVolumetric(benchmark::State& state) {
  RenderScene scene = load_render_scene(std::filesystem::path(SCATTERLAB_SOURCE_DIR) /
                                        "data/scenes/milk-sphere.toml");
  scene.width = 32;
  scene.height = 24;
  scene.samples = 16;
  RenderSettings settings;
  settings.method = RenderMethod::volumetric;
  settings.threads = 1;
  VolumetricCounters counters;
  for (auto _ : state) {
    const VolumetricResult result = render_volumetric(scene, settings);
    counters = result.counters;
    benchmark::DoNotOptimize(result.image.channels[0].values.data());
  }
  state.counters["paths"] = benchmark::Counter(static_cast<double>(counters.paths),
                                               benchmark::Counter::kIsIterationInvariantRate);
  state.counters["collisions_per_path"] =
      static_cast<double>(counters.collisions) / static_cast<double>(counters.paths);
}
BENCHMARK(BM_RenderVolumetric)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
}  // namespace scatterlab
