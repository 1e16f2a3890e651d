// The memory estimates (core/memory_budget.hpp) against what a run really allocates: this program
// counts every byte operator new hands out and holds the peak of a run over its start to the
// estimate the run is checked with. An estimate may be high by a stated factor, never low.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <new>

#include "scatterlab/core/memory_budget.hpp"
#include "scatterlab/transport/engine.hpp"
#include "scatterlab/transport/searchlight.hpp"
#include "scatterlab/transport/simulate.hpp"

namespace {

std::atomic<std::uint64_t> live_bytes{0};
std::atomic<std::uint64_t> peak_bytes{0};

// Each block carries its size in front, so that delete knows what it gives back.
constexpr std::size_t header = alignof(std::max_align_t);

void* counted_new(std::size_t size) {
  void* block = std::malloc(size + header);
  if (block == nullptr) throw std::bad_alloc();
  *static_cast<std::size_t*>(block) = size;
  const std::uint64_t now = live_bytes.fetch_add(size) + size;
  std::uint64_t peak = peak_bytes.load();
  while (now > peak && !peak_bytes.compare_exchange_weak(peak, now)) {
  }
  return static_cast<char*>(block) + header;
}

void counted_delete(void* pointer) noexcept {
  if (pointer == nullptr) return;
  char* block = static_cast<char*>(pointer) - header;
  live_bytes.fetch_sub(*reinterpret_cast<std::size_t*>(block));
  std::free(block);
}

}  // namespace

void* operator new(std::size_t size) {
  return counted_new(size);
}
void* operator new[](std::size_t size) {
  return counted_new(size);
}
void operator delete(void* pointer) noexcept {
  counted_delete(pointer);
}
void operator delete[](void* pointer) noexcept {
  counted_delete(pointer);
}
void operator delete(void* pointer, std::size_t) noexcept {
  counted_delete(pointer);
}
void operator delete[](void* pointer, std::size_t) noexcept {
  counted_delete(pointer);
}

namespace scatterlab {
namespace {

// The most bytes `action` held at once beyond what was live when it started.
template <typename Action>
std::uint64_t peak_of(Action&& action) {
  const std::uint64_t before = live_bytes.load();
  peak_bytes.store(before);
  action();
  return peak_bytes.load() - before;
}

// Estimates may be high by this factor at most: they count every result array at once, as the
// last moments of a run may hold them, though most runs hold fewer.
constexpr double stated_factor = 1.5;

void expect_within_factor(std::uint64_t estimate, std::uint64_t allocated) {
  EXPECT_GE(estimate, allocated) << "estimated " << format_bytes(estimate) << ", allocated "
                                 << format_bytes(allocated);
  EXPECT_LE(static_cast<double>(estimate), stated_factor * static_cast<double>(allocated))
      << "estimated " << format_bytes(estimate) << ", allocated " << format_bytes(allocated);
}

// The estimate the run of `spec` is checked with, against what `run` allocates at its peak.
template <typename Spec, typename Run>
void expect_estimate_covers(const Spec& spec, Run run) {
  const std::uint64_t estimate = transport_memory(transport_problem(spec), 1, false).bytes();
  const std::uint64_t allocated = peak_of([&] { (void)run(spec); });
  expect_within_factor(estimate, allocated);
}

TEST(MemoryEstimates, SimulationWithEveryTallySplitByOrder) {
  for (const int threads : {1, 2, 4}) {
    InfiniteMediumSpec spec;
    spec.tallies.split_by_order = true;
    spec.tallies.fluence_spherical = true;
    spec.source = SourceKind::point;
    spec.grid.r.bins = 30;
    spec.run.photons = 400;
    spec.run.batches = 8;
    spec.run.threads = threads;
    expect_estimate_covers(spec, [](const auto& s) { return run_infinite_medium(s); });
  }
}

TEST(MemoryEstimates, SimulationWithoutRadiance) {
  InfiniteMediumSpec spec;
  spec.tallies.radiance = false;
  spec.grid.r.bins = 2000;
  spec.grid.z.bins = 500;
  spec.run.photons = 200;
  spec.run.batches = 4;
  spec.run.threads = 2;
  expect_estimate_covers(spec, [](const auto& s) { return run_infinite_medium(s); });
}

TEST(MemoryEstimates, TrackLengthEstimatorWithItsCrossingLists) {
  InfiniteMediumSpec spec;
  spec.tallies.estimator = Estimator::track_length;
  spec.tallies.radiance = false;
  spec.grid.r.bins = 3000;
  spec.grid.z.bins = 300;
  spec.run.photons = 200;
  spec.run.batches = 4;
  spec.run.threads = 3;
  expect_estimate_covers(spec, [](const auto& s) { return run_infinite_medium(s); });
}

TEST(MemoryEstimates, Searchlight) {
  HalfSpaceSpec spec;
  spec.grid.r.bins = 1000;
  spec.grid.z.bins = 500;
  spec.run.photons = 200;
  spec.run.batches = 4;
  spec.run.threads = 2;
  expect_estimate_covers(spec, [](const auto& s) { return run_half_space(s); });
}

}  // namespace
}  // namespace scatterlab
