#pragma once
// Runs photons in independent, seeded batches over threads and ranks and folds every tally cell
// into batch statistics. Shared by every random-walk kernel (infinite medium, half-space, ...): a
// kernel only says how to transport photons [first, last) into a buffer of per-cell sums.
//
// Results are bitwise identical for any number of threads and ranks, and for a run resumed from a
// checkpoint: each photon's random stream depends only on (seed, photon index), each batch is
// transported by one thread in photon order into a zeroed buffer, and every cell folds the batches
// with the same Welford arithmetic in batch order.
//
// Batches go to ranks in groups: group g holds batch (first + g * ranks + q) of each rank q. On a
// rank, threads take the groups from a shared counter as they become free, so a slow or
// descheduled thread holds up no other, each into one of a ring of score buffers: 2 x threads - 1
// of them, so that a thread may run up to threads - 1 groups ahead of the slowest before it waits.
// Groups are folded strictly in order, by whichever thread finds the next one complete; threads
// that wait for a buffer, or have no batch left, fold parts of the cells beside it (a cell's
// arithmetic does not depend on who folds it). With several ranks the folding thread first
// exchanges the group's sums, so that each rank holds its contiguous slice of the cells of every
// batch of the group, and folds those in batch order: memory per rank is independent of the rank
// count. OpenMP may grant fewer threads than asked (OMP_DYNAMIC, OMP_THREAD_LIMIT): the team
// shares the same ring, to the same bits.
//
// A stop request is read between slices of every batch. A batch cut short on any rank abandons
// its group on all of them (the group's flags are combined across ranks before anything is
// folded), so a stopped run holds exactly the whole groups folded before it, and resumes to the
// same bits. A thread that fails (an allocation refused, a walk that throws) hands in its batch
// cut short, so that the run stops the same way, and run_batches throws the failure.
//
// The scheduler (batch_runner.cpp) is one piece of code for every kernel: it calls the kernel
// once per slice of photons, through SliceKernel.

#include <algorithm>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

#include "scatterlab/core/memory_budget.hpp"
#include "scatterlab/transport/run_control.hpp"
#include "scatterlab/transport/run_settings.hpp"

namespace scatterlab {

// Where a run stands after a group of batches: how many of its batches (and the photons in them)
// are done, and how many of those were done before this process started (resumed from a
// checkpoint), so that a rate or an ETA can count this process's own work only.
struct BatchProgress {
  std::uint64_t batches_done = 0;
  std::uint64_t batches = 0;
  std::uint64_t batches_resumed = 0;
  std::uint64_t photons_done = 0;
  std::uint64_t photons_resumed = 0;
  // Scattering events per photon of the batches this process has folded (0 before the first).
  double events_per_photon = 0.0;

  double fraction() const {
    return static_cast<double>(batches_done) / static_cast<double>(batches);
  }
};

// Called on the calling thread (each rank's master) with the latest folded state, after each
// batch that thread transports and once at the end, so that a callback may poll for signals (as
// Python's does) within a batch's time.
using ProgressCallback = std::function<void(const BatchProgress&)>;

// Photons [first, last) of batch b: the first N mod B batches hold one photon more.
struct BatchRange {
  std::uint64_t first;
  std::uint64_t last;
};

inline BatchRange batch_range(std::uint64_t photons, std::uint64_t batches, std::uint64_t b) {
  const std::uint64_t base = photons / batches, extra = photons % batches;
  const std::uint64_t first = b * base + std::min(b, extra);
  return {first, first + base + (b < extra ? 1 : 0)};
}

struct BatchOutcome {
  // On the root rank; empty on the others.
  std::vector<double> mean;            // per photon, for every tally cell
  std::vector<double> standard_error;  // of that mean, from the batch-to-batch spread
  std::uint64_t scattering_events = 0;
  std::uint64_t batches_done = 0;  // < the batches asked for when stopped early
  std::uint64_t photons_done = 0;  // photons in those batches
  // Done before this process started, by the run it resumed (0 when starting afresh); the wall
  // time is known on the root rank only.
  std::uint64_t batches_resumed = 0;
  std::uint64_t photons_resumed = 0;
  double resumed_wall_seconds = 0.0;
  // This process's time in the random walk (scoring included), summed over its threads, and the
  // scattering events it walked: the cost per event without set-up, folding and finishing.
  double walk_seconds = 0.0;
  std::uint64_t walk_events = 0;
  int threads = 1;        // per rank: what OpenMP granted
  int threads_asked = 1;  // per rank: run.threads (or OpenMP's count for 0), at most the batches
  int ranks = 1;

  bool complete(const RunSettings& run) const { return batches_done == run.batches; }
};

// The threads of each rank: run.threads, or OpenMP's count for 0; never more than the batches.
int batch_threads(const RunSettings& run);

// The ring of score buffers of each rank: 2 x threads - 1, never more than the rank's groups.
std::size_t score_buffers(int threads, std::uint64_t batches, int ranks);

// What run_batches holds at its peak on the root rank, for `cells` values per batch: the ring of
// score buffers; the statistics of the rank's slice (mean and sum of squares); at the end the
// whole state gathered on the root and its standard error; with several ranks, a group's
// received slices (a batch's worth of cells); when resuming, the saved state the caller
// holds (RunControl::resume_from).
MemoryEstimate batch_memory(std::size_t cells, int threads, std::uint64_t batches, int ranks,
                            bool resuming);

namespace detail {

// Photons between two looks at the stop flag: a few milliseconds of transport at most, so that a
// stop is honoured within a fraction of a second however long a batch is, and few enough looks
// that their cost is lost in the walk's.
constexpr std::uint64_t kStopPollPhotons = 1024;

// A batch being folded in parts of kFoldPart cells (about 30 us each), so that threads waiting
// for a buffer, or done with their batches, fold parts of it beside the folding thread.
constexpr std::size_t kFoldPart = std::size_t{1} << 15;

}  // namespace detail

// What the scheduler runs: each thread starts its own worker once, with its working memory, and
// asks it for slices of kStopPollPhotons photons or fewer. A worker adds the scores of photons
// [first, last) to sums[0, cells) and returns their scattering events; the walk itself stays
// specialised for its scene (WalkKernel below), so that the one virtual call per slice is all
// the scheduler adds.
class SliceKernel {
 public:
  class Worker {
   public:
    virtual ~Worker() = default;
    virtual std::uint64_t run(std::uint64_t first, std::uint64_t last, double* sums) = 0;
  };

  virtual ~SliceKernel() = default;
  virtual std::unique_ptr<Worker> start_worker() const = 0;
};

// With a communicator, every rank calls this with the same arguments.
BatchOutcome run_batches(const RunSettings& run, std::size_t cells, const SliceKernel& kernel,
                         const ProgressCallback& progress, const RunControl& control = {});

// A random walk as a SliceKernel. `Walk` provides
//   Scratch make_scratch() const;        per-thread working memory, made once per thread
//   std::uint64_t run(std::uint64_t first, std::uint64_t last, double* sums, Scratch&) const;
template <class Walk>
class WalkKernel final : public SliceKernel {
 public:
  explicit WalkKernel(const Walk& walk) : walk_(walk) {}

  std::unique_ptr<Worker> start_worker() const override {
    return std::make_unique<WalkWorker>(walk_);
  }

 private:
  class WalkWorker final : public Worker {
   public:
    explicit WalkWorker(const Walk& walk) : walk_(walk), scratch_(walk.make_scratch()) {}
    std::uint64_t run(std::uint64_t first, std::uint64_t last, double* sums) override {
      return walk_.run(first, last, sums, scratch_);
    }

   private:
    const Walk& walk_;
    decltype(std::declval<const Walk&>().make_scratch()) scratch_;
  };

  const Walk& walk_;
};

template <class Walk>
  requires(!std::derived_from<Walk, SliceKernel>)
BatchOutcome run_batches(const RunSettings& run, std::size_t cells, const Walk& walk,
                         const ProgressCallback& progress, const RunControl& control = {}) {
  return run_batches(run, cells, WalkKernel<Walk>(walk), progress, control);
}

}  // namespace scatterlab
