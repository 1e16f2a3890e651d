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
// count.
//
// A stop request is read between slices of every batch (detail::transport_batch). A batch cut
// short on any rank abandons its group on all of them (the group's flags are combined across
// ranks before anything is folded), so a stopped run holds exactly the whole groups folded before
// it, and resumes to the same bits.

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "scatterlab/core/error.hpp"
#include "scatterlab/core/memory_budget.hpp"
#include "scatterlab/tally/batch_statistics.hpp"
#include "scatterlab/transport/communicator.hpp"
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
  int threads = 1;        // per rank: what OpenMP granted
  int threads_asked = 1;  // per rank: run.threads (or OpenMP's count for 0), at most the batches
  int ranks = 1;

  bool complete(const RunSettings& run) const { return batches_done == run.batches; }
};

// The threads of each rank: run.threads, or OpenMP's count for 0; never more than the batches.
inline int batch_threads(const RunSettings& run) {
  const int asked = run.threads > 0 ? run.threads : omp_get_max_threads();
  return static_cast<int>(std::min<std::uint64_t>(run.batches, static_cast<std::uint64_t>(asked)));
}

// The ring of score buffers of each rank: 2 x threads - 1, never more than the rank's groups.
inline std::size_t score_buffers(int threads, std::uint64_t batches, int ranks) {
  const auto per_rank = static_cast<std::uint64_t>(ranks);
  const std::uint64_t groups = (batches + per_rank - 1) / per_rank;
  const std::uint64_t ring = 2 * static_cast<std::uint64_t>(threads) - 1;
  return static_cast<std::size_t>(std::max<std::uint64_t>(1, std::min(ring, groups)));
}

// What run_batches holds at its peak on the root rank, for `cells` values per batch: the ring of
// score buffers; the statistics of the rank's slice (mean and sum of squares); at the end the
// whole state gathered on the root and its standard error; with several ranks, a group's
// received slices (a batch's worth of cells); when resuming, the saved state the caller
// holds (RunControl::resume_from).
inline MemoryEstimate batch_memory(std::size_t cells, int threads, std::uint64_t batches, int ranks,
                                   bool resuming) {
  const auto values = static_cast<std::uint64_t>(cells);
  MemoryEstimate need;
  need.add_doubles(fmt::format("score buffers of {} tally values (2 per thread but one)", values),
                   values, score_buffers(threads, batches, ranks));
  need.add_doubles(fmt::format("arrays of {} tally values (batch statistics and results)", values),
                   values, 5);
  if (ranks > 1) need.add_doubles("exchange buffer (a group's slices)", values, 1);
  if (resuming) need.add_doubles("arrays of the checkpoint resumed from", values, 2);
  return need;
}

namespace detail {

// Rank p owns cells [cells * p / ranks, cells * (p + 1) / ranks).
inline std::vector<std::size_t> cell_slices(std::size_t cells, int ranks) {
  std::vector<std::size_t> counts(static_cast<std::size_t>(ranks));
  const auto r = static_cast<std::size_t>(ranks);
  for (std::size_t p = 0; p < r; ++p) counts[p] = cells * (p + 1) / r - cells * p / r;
  return counts;
}

constexpr std::uint64_t kStopFlag = 1, kCheckpointFlag = 2, kAbandonFlag = 4;

// Photons between two looks at the stop flag: a few milliseconds of transport at most, so that a
// stop is honoured within a fraction of a second however long a batch is, and few enough looks
// that their cost is lost in the walk's.
constexpr std::uint64_t kStopPollPhotons = 1024;

// Transports one batch into `sums` in slices of kStopPollPhotons photons, in photon order (the
// same arithmetic as one call, so the same bits). Returns false when a stop was requested (from
// outside, or by the runner itself once it has decided to end) before the batch was complete: its
// sums are then partial and must not be folded.
template <class Walk, class Scratch>
bool transport_batch(const Walk& walk, BatchRange range, double* sums, Scratch& scratch,
                     const std::atomic<bool>* stop_requested, const std::atomic<bool>& halted,
                     std::uint64_t& scatterings) {
  for (std::uint64_t first = range.first; first < range.last; first += kStopPollPhotons) {
    if ((stop_requested != nullptr && stop_requested->load(std::memory_order_relaxed)) ||
        halted.load(std::memory_order_relaxed)) {
      return false;
    }
    const std::uint64_t last = std::min(range.last, first + kStopPollPhotons);
    scatterings += walk.run(first, last, sums, scratch);
  }
  return true;
}

// One buffer of the ring: the group whose batch it last received (none yet: ~0), whether that
// batch was whole or cut short, and its scattering events.
struct RingSlot {
  std::uint64_t group = ~std::uint64_t{0};
  bool whole = false;
  std::uint64_t scatterings = 0;
};

// A batch being folded in parts of kFoldPart cells (about 30 us each), so that threads waiting
// for a buffer, or done with their batches, fold parts of it beside the folding thread.
constexpr std::size_t kFoldPart = std::size_t{1} << 15;
static_assert(kFoldPart % BatchStatistics::kBlock == 0, "parts folded at once share no block");
struct FoldJob {
  double* sums = nullptr;
  std::uint64_t batch = 0;
  double photons = 0.0;
  std::size_t parts = 0;
};

}  // namespace detail

// `Walk` provides
//   Scratch make_scratch() const;        per-thread working memory, made once per thread
//   std::uint64_t run(std::uint64_t first, std::uint64_t last, double* sums, Scratch&) const;
// where run adds the scores of photons [first, last) to sums[0, cells) and returns the number
// of scattering events. With a communicator, every rank calls this with the same arguments.
template <class Walk>
BatchOutcome run_batches(const RunSettings& run, std::size_t cells, const Walk& walk,
                         const ProgressCallback& progress, const RunControl& control = {}) {
  SerialCommunicator serial;
  Communicator& world = control.communicator != nullptr ? *control.communicator : serial;
  const int ranks = world.size();
  const auto rank = static_cast<std::size_t>(world.rank());
  const auto rank_count = static_cast<std::uint64_t>(ranks);
  const std::uint64_t photons = run.photons;
  const std::uint64_t batches = run.batches;
  // Every rank uses the root's thread count, so that all hold rings of the same size.
  const int threads =
      static_cast<int>(world.broadcast_from_root(static_cast<std::uint64_t>(batch_threads(run))));

  const std::vector<std::size_t> slices = detail::cell_slices(cells, ranks);
  const std::size_t slice = slices[rank];

  // Resume: the root's saved state, dealt out slice by slice. Whether it fits this run is checked
  // on the root and agreed by all ranks, so that a refusal ends every rank rather than leaving
  // the others waiting for the root.
  const RunState* resume = world.is_root() ? control.resume_from : nullptr;
  std::string misfit;
  if (resume != nullptr && (resume->mean.size() != cells || resume->squares.size() != cells)) {
    misfit = fmt::format("holds {} values per Welford array but this run's tallies have {} cells",
                         resume->mean.size(), cells);
  } else if (resume != nullptr && resume->batches_folded > batches) {
    misfit =
        fmt::format("has folded {} batches but this run has {}", resume->batches_folded, batches);
  }
  if (world.broadcast_from_root(misfit.empty() ? 0 : 1) != 0) {
    throw InputError("--resume",
                     fmt::format("the checkpoint '{}' {}", control.resume_source,
                                 misfit.empty() ? "does not fit this run (see rank 0)" : misfit),
                     "a checkpoint written by this run (same parameters and seed)");
  }
  const std::uint64_t start = world.broadcast_from_root(resume ? resume->batches_folded : 0);
  BatchStatistics statistics(slice);
  if (start > 0) {
    std::vector<double> mean = world.scatter_from_root(
        resume ? std::span<const double>(resume->mean) : std::span<const double>(), slices);
    std::vector<double> squares = world.scatter_from_root(
        resume ? std::span<const double>(resume->squares) : std::span<const double>(), slices);
    statistics = BatchStatistics(std::move(mean), std::move(squares));
  }

  const std::uint64_t groups = (batches - start + rank_count - 1) / rank_count;
  const std::size_t slots = score_buffers(threads, batches - start, ranks);
  std::vector<std::vector<double>> ring(slots);
  std::vector<detail::RingSlot> ring_state(slots);
  // A buffer holds the cells in owner order, so it is sent as it is: slices[p] values to rank p.
  std::vector<double> received;
  std::vector<std::size_t> receive_counts;
  if (ranks > 1) {
    received.resize(rank_count * slice);
    receive_counts.assign(static_cast<std::size_t>(ranks), slice);
  }

  // Shared by the threads: the next group to take; under ring_mutex, the ring's states and the
  // next group to fold (a group's buffer is free once it is folded); `halted` once the run ends
  // early, so that no thread takes or finishes another batch.
  std::atomic<std::uint64_t> next_group{0};
  std::atomic<bool> halted{false};  // set, under ring_mutex, when the ranks agree to stop
  std::mutex ring_mutex;
  std::condition_variable buffer_freed;
  std::uint64_t next_to_fold = 0;
  // The batch being folded in parts: under ring_mutex its job and generation; the next part to
  // take, tagged with the generation in its high 32 bits so that a thread holding an earlier
  // job's copy takes nothing (parts are left while it is below job.parts); the parts done.
  detail::FoldJob job;
  std::uint64_t job_generation = 0;
  std::atomic<std::uint64_t> job_next{0};
  std::atomic<std::size_t> job_done{0};

  // Held by the thread that folds; everything below it is touched under fold_mutex only (or on
  // the calling thread before and after the parallel region).
  std::mutex fold_mutex;
  std::uint64_t scatterings = resume != nullptr ? resume->scattering_events : 0;
  const auto clock_start = std::chrono::steady_clock::now();
  const double resumed_wall_seconds = resume != nullptr ? resume->wall_seconds : 0.0;
  auto last_checkpoint = clock_start;
  std::uint64_t last_checkpoint_batches = start;
  std::uint64_t done = start;
  std::exception_ptr failure;

  // The latest folded state, for the calling thread to report (ProgressCallback).
  std::mutex progress_mutex;
  BatchProgress latest;
  bool unreported = false;
  auto report_progress = [&]() {
    if (!progress) return;
    BatchProgress now;
    {
      std::lock_guard<std::mutex> lock(progress_mutex);
      if (!unreported) return;
      now = latest;
      unreported = false;
    }
    progress(now);
  };

  // The whole state, gathered on the root (a collective: every rank calls it).
  auto gather_state = [&]() {
    RunState state;
    state.batches_folded = done;
    state.scattering_events = world.sum(scatterings);
    state.wall_seconds =
        resumed_wall_seconds +
        std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
    state.mean = world.gather_to_root(statistics.mean(), slices);
    state.squares = world.gather_to_root(statistics.squares(), slices);
    return state;
  };

  // Folds the parts of `work` (generation `generation`) that no thread has taken yet.
  auto fold_parts = [&](const detail::FoldJob& work, std::uint64_t generation) {
    const std::uint64_t tag = (generation & 0xffffffffu) << 32;
    for (;;) {
      std::uint64_t next = job_next.load();
      do {
        if ((next & ~std::uint64_t{0xffffffffu}) != tag || (next & 0xffffffffu) >= work.parts) {
          return;
        }
      } while (!job_next.compare_exchange_weak(next, next + 1));
      const std::size_t begin = static_cast<std::size_t>(next & 0xffffffffu) * detail::kFoldPart;
      statistics.add_batch(work.batch, work.sums, work.photons, begin,
                           std::min(slice, begin + detail::kFoldPart));
      job_done.fetch_add(1);
    }
  };

  // Folds batch b's sums into the statistics, with the help of any thread that is waiting.
  auto fold_batch = [&](std::uint64_t b, double* sums) {
    const BatchRange range = batch_range(photons, batches, b);
    const auto batch_photons = static_cast<double>(range.last - range.first);
    const std::size_t parts = (slice + detail::kFoldPart - 1) / detail::kFoldPart;
    if (threads == 1 || parts < 2) {
      statistics.add_batch(b, sums, batch_photons, 0, slice);
      return;
    }
    detail::FoldJob work{sums, b, batch_photons, parts};
    std::uint64_t generation = 0;
    {
      std::lock_guard<std::mutex> lock(ring_mutex);
      generation = ++job_generation;
      job = work;
      job_done = 0;
      job_next = (generation & 0xffffffffu) << 32;
    }
    buffer_freed.notify_all();
    fold_parts(work, generation);
    while (job_done.load() < parts) std::this_thread::yield();  // parts others took
  };

  // Waits under ring_mutex until ready() or the run halts, folding parts of the batch being
  // folded meanwhile.
  auto wait_helping = [&](auto ready) {
    std::unique_lock<std::mutex> lock(ring_mutex);
    const auto parts_left = [&] { return (job_next.load() & 0xffffffffu) < job.parts; };
    for (;;) {
      buffer_freed.wait(lock, [&] { return ready() || halted || parts_left(); });
      if (ready() || halted) return;
      const detail::FoldJob work = job;
      const std::uint64_t generation = job_generation;
      lock.unlock();
      fold_parts(work, generation);
      lock.lock();
    }
  };

  // Folds group g, whose batch on this rank is in `sums` (`whole`, or cut short by a stop).
  // Every rank folds the same groups in the same order: the flags are combined first, so that a
  // batch cut short anywhere abandons the group everywhere.
  auto fold_group = [&](std::uint64_t g, bool whole, std::uint64_t batch_scatterings,
                        std::vector<double>& sums) {
    const std::uint64_t first = start + g * rank_count;
    const std::uint64_t end_of_group = std::min(batches, first + rank_count);
    std::uint64_t flags = 0;
    // A stop request shows as a cut batch: every batch in flight is cut short, and any taken
    // after it is cut before its first photon, so the whole batches before it are still folded.
    if (!whole) flags |= detail::kStopFlag | detail::kAbandonFlag;
    if (failure != nullptr) flags |= detail::kStopFlag;
    const auto now = std::chrono::steady_clock::now();
    const CheckpointPolicy& policy = control.checkpoint;
    const bool due =
        (policy.every_batches > 0 &&
         end_of_group - last_checkpoint_batches >= policy.every_batches) ||
        (policy.every_seconds > 0.0 &&
         std::chrono::duration<double>(now - last_checkpoint).count() >= policy.every_seconds);
    if (world.is_root() && due && end_of_group < batches && control.save_checkpoint) {
      flags |= detail::kCheckpointFlag;
    }
    flags = world.bitwise_or(flags);
    const bool abandon = (flags & detail::kAbandonFlag) != 0;
    if (abandon) flags &= ~detail::kCheckpointFlag;
    // Stopping early saves the state too, so that the run can be resumed from there, unless the
    // last checkpoint (or the one resumed from) already holds it.
    const std::uint64_t held = abandon ? done : end_of_group;
    if ((flags & detail::kStopFlag) && held < batches && held > last_checkpoint_batches &&
        control.save_checkpoint) {
      flags |= detail::kCheckpointFlag;
    }
    if (!abandon) {
      double* group_sums = sums.data();
      if (ranks > 1) {
        // This rank's batch goes out in the owners' slices (and is cleared for its buffer's next
        // batch); back come this rank's slices of every batch of the group, in rank order.
        world.all_to_all(sums, slices, received, receive_counts);
        std::fill(sums.begin(), sums.end(), 0.0);
        group_sums = received.data();
      }
      for (std::uint64_t b = first; b < end_of_group; ++b) {
        fold_batch(b, group_sums + (b - first) * slice);
      }
      scatterings += batch_scatterings;
      done = end_of_group;
      std::lock_guard<std::mutex> lock(progress_mutex);
      latest = {done, batches, start, batch_range(photons, batches, done).first,
                batch_range(photons, batches, start).first};
      unreported = true;
    }
    if (flags & detail::kCheckpointFlag) {
      try {
        const RunState saved = gather_state();
        if (world.is_root()) control.save_checkpoint(saved);
      } catch (...) {
        failure = std::current_exception();  // stops every rank after the next group
      }
      last_checkpoint = std::chrono::steady_clock::now();
      last_checkpoint_batches = done;
    }
    if (flags & detail::kStopFlag) {
      std::lock_guard<std::mutex> lock(ring_mutex);
      halted = true;
    }
  };

  // Folds every group that is next in order and complete, unless another thread is folding: that
  // one looks again after it lets go, so that a group completed meanwhile is never left behind
  // and every complete group is folded before the threads leave the parallel region.
  auto fold_ready = [&]() {
    auto next_is_complete = [&] {
      return !halted && next_to_fold < groups &&
             ring_state[next_to_fold % slots].group == next_to_fold;
    };
    for (;;) {
      std::unique_lock<std::mutex> folding(fold_mutex, std::try_to_lock);
      if (!folding.owns_lock()) return;
      for (;;) {
        detail::RingSlot slot;
        {
          std::lock_guard<std::mutex> lock(ring_mutex);
          if (!next_is_complete()) break;
          slot = ring_state[next_to_fold % slots];
        }
        fold_group(slot.group, slot.whole, slot.scatterings, ring[slot.group % slots]);
        {
          std::lock_guard<std::mutex> lock(ring_mutex);
          ++next_to_fold;
        }
        buffer_freed.notify_all();
      }
      folding.unlock();
      std::lock_guard<std::mutex> lock(ring_mutex);
      if (!next_is_complete()) return;
    }
  };

  // A thread that cannot work (an allocation refused, a walk that threw) keeps the first such
  // failure here and hands in the group it takes cut short, so that every rank stops after the
  // whole groups before it; the failure is thrown once the threads have left the region, where an
  // exception may pass.
  std::mutex thread_failure_mutex;
  std::exception_ptr thread_failure;
  auto keep_failure = [&](std::exception_ptr error) {
    std::lock_guard<std::mutex> lock(thread_failure_mutex);
    if (!thread_failure) thread_failure = std::move(error);
  };
  std::atomic<bool> ring_failed{false};
  std::atomic<int> granted{threads};

#pragma omp parallel num_threads(threads)
  {
    // OpenMP may grant fewer threads than asked (OMP_DYNAMIC, OMP_THREAD_LIMIT, a nested region):
    // the team shares the work by its own size.
    const auto team = static_cast<std::size_t>(omp_get_num_threads());
    const auto t = static_cast<std::size_t>(omp_get_thread_num());
    if (t == 0) granted = static_cast<int>(team);
    // Each thread first touches its own share of the ring.
    try {
      for (std::size_t s = t; s < slots; s += team) ring[s].assign(cells, 0.0);
    } catch (...) {
      keep_failure(std::current_exception());
      ring_failed = true;
    }
#pragma omp barrier
    std::optional<decltype(walk.make_scratch())> scratch;
    try {
      if (!ring_failed) scratch.emplace(walk.make_scratch());
    } catch (...) {
      keep_failure(std::current_exception());
    }
    for (;;) {
      const std::uint64_t g = next_group.fetch_add(1);
      if (g >= groups) {
        wait_helping([&] { return next_to_fold >= groups; });  // help fold the last batches
        break;
      }
      wait_helping([&] { return g < next_to_fold + slots; });
      if (halted) break;
      const std::uint64_t batch = start + g * rank_count + rank;
      std::uint64_t batch_scatterings = 0;
      bool whole = scratch.has_value();
      if (scratch && batch < batches) {
        try {
          whole = detail::transport_batch(walk, batch_range(photons, batches, batch),
                                          ring[g % slots].data(), *scratch,
                                          control.stop_requested, halted, batch_scatterings);
        } catch (...) {
          keep_failure(std::current_exception());
          scratch.reset();
          whole = false;
        }
      }
      {
        std::lock_guard<std::mutex> lock(ring_mutex);
        ring_state[g % slots] = {g, whole, batch_scatterings};
      }
      fold_ready();
      if (t == 0) report_progress();
      if (!scratch) break;
    }
  }
  report_progress();

  RunState state = gather_state();
  if (thread_failure) std::rethrow_exception(thread_failure);
  if (failure) std::rethrow_exception(failure);
  BatchOutcome outcome;
  outcome.batches_done = done;
  outcome.photons_done = batch_range(photons, batches, done).first;  // photons before batch `done`
  outcome.standard_error = BatchStatistics::standard_error_from_squares(state.squares, done);
  if (!world.is_root()) outcome.standard_error.clear();
  outcome.mean = std::move(state.mean);
  outcome.scattering_events = state.scattering_events;
  outcome.batches_resumed = start;
  outcome.photons_resumed = batch_range(photons, batches, start).first;
  outcome.resumed_wall_seconds = resumed_wall_seconds;
  outcome.threads = granted;
  outcome.threads_asked = threads;
  outcome.ranks = ranks;
  return outcome;
}

}  // namespace scatterlab
