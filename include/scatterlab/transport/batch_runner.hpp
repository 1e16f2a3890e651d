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
// Work is dealt in rounds of ranks x threads batches: thread t of rank q transports batch
// (first of round + q * threads + t). Each rank owns a contiguous slice of the cells; after a
// round the per-batch sums are exchanged so that each rank holds its slice of every batch of the
// round, and its threads fold sub-slices in batch order. Memory per rank is independent of the
// rank count: a buffer per thread, the round's received slices (threads x cells values) and the
// statistics of its slice.
//
// A stop request is read between slices of every batch (detail::transport_batch), not only
// between rounds: a round that a stop cuts short on any rank is abandoned on all of them, so a
// stopped run holds exactly the whole rounds folded before it, and resumes to the same bits.

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <string>
#include <vector>

#include "scatterlab/core/error.hpp"
#include "scatterlab/core/memory_budget.hpp"
#include "scatterlab/tally/batch_statistics.hpp"
#include "scatterlab/transport/communicator.hpp"
#include "scatterlab/transport/run_control.hpp"
#include "scatterlab/transport/run_settings.hpp"

namespace scatterlab {

// Where a run stands after a round of batches: how many of its batches (and the photons in them)
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

// Called on the calling thread (the root rank's master) after every round of batches.
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
  int threads = 1;                 // per rank
  int ranks = 1;

  bool complete(const RunSettings& run) const { return batches_done == run.batches; }
};

// The threads of each rank: run.threads, or OpenMP's count for 0; never more than the batches.
inline int batch_threads(const RunSettings& run) {
  const int asked = run.threads > 0 ? run.threads : omp_get_max_threads();
  return static_cast<int>(std::min<std::uint64_t>(run.batches, static_cast<std::uint64_t>(asked)));
}

// What run_batches holds at its peak on the root rank, for `cells` values per batch: a score
// buffer per thread; the statistics of the rank's slice (mean and sum of squares); at the end the
// whole state gathered on the root and its standard error; with several ranks, the round's send
// and receive buffers (a thread's worth of every cell each); when resuming, the saved state the
// caller holds (RunControl::resume_from).
inline MemoryEstimate batch_memory(std::size_t cells, int threads, int ranks, bool resuming) {
  const auto values = static_cast<std::uint64_t>(cells);
  const auto per_rank = static_cast<std::uint64_t>(threads);
  MemoryEstimate need;
  need.add_doubles(fmt::format("score buffers of {} tally values (one per thread)", values), values,
                   per_rank);
  need.add_doubles(fmt::format("arrays of {} tally values (batch statistics and results)", values),
                   values, 5);
  if (ranks > 1) need.add_doubles("exchange buffers (two per thread)", values, 2 * per_rank);
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
// same arithmetic as one call, so the same bits). Returns false when a stop was requested before
// the batch was complete: its sums are then partial and must not be folded.
template <class Walk, class Scratch>
bool transport_batch(const Walk& walk, BatchRange range, double* sums, Scratch& scratch,
                     const std::atomic<bool>* stop_requested, std::uint64_t& scatterings) {
  for (std::uint64_t first = range.first; first < range.last; first += kStopPollPhotons) {
    if (stop_requested != nullptr && stop_requested->load(std::memory_order_relaxed)) {
      return false;
    }
    const std::uint64_t last = std::min(range.last, first + kStopPollPhotons);
    scatterings += walk.run(first, last, sums, scratch);
  }
  return true;
}

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
  const std::uint64_t photons = run.photons;
  const std::uint64_t batches = run.batches;
  // Every rank uses the root's thread count, so that all agree on which batch is whose.
  const int threads =
      static_cast<int>(world.broadcast_from_root(static_cast<std::uint64_t>(batch_threads(run))));
  const auto thread_count = static_cast<std::size_t>(threads);
  const std::uint64_t per_round = static_cast<std::uint64_t>(ranks) * thread_count;

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

  // One score buffer per thread; with several ranks, the round's slices of every batch.
  std::vector<std::vector<double>> sums(thread_count, std::vector<double>(cells, 0.0));
  std::vector<std::uint64_t> scatterings(thread_count, 0);
  std::vector<int> abandoned(thread_count, 0);  // by thread: its batch of the round was cut short
  if (resume != nullptr) scatterings[0] = resume->scattering_events;
  std::vector<double> send, received;
  std::vector<std::size_t> send_counts, receive_counts;
  if (ranks > 1) {
    send.resize(thread_count * cells);
    received.resize(per_round * slice);
    for (const std::size_t count : slices) send_counts.push_back(thread_count * count);
    receive_counts.assign(static_cast<std::size_t>(ranks), thread_count * slice);
  }

  const auto clock_start = std::chrono::steady_clock::now();
  const double resumed_wall_seconds = resume != nullptr ? resume->wall_seconds : 0.0;
  auto last_checkpoint = clock_start;
  std::uint64_t last_checkpoint_batches = start;
  std::uint64_t done = start;
  std::uint64_t round_flags = 0;  // written by the master before the round's second barrier
  std::exception_ptr failure;

  // The whole state, gathered on the root (a collective: every rank calls it).
  auto gather_state = [&]() {
    RunState state;
    state.batches_folded = done;
    std::uint64_t local = 0;
    for (const std::uint64_t s : scatterings) local += s;
    state.scattering_events = world.sum(local);
    state.wall_seconds =
        resumed_wall_seconds +
        std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
    state.mean = world.gather_to_root(statistics.mean(), slices);
    state.squares = world.gather_to_root(statistics.squares(), slices);
    return state;
  };

#pragma omp parallel num_threads(threads)
  {
    const auto t = static_cast<std::size_t>(omp_get_thread_num());
    auto scratch = walk.make_scratch();
    // Each thread folds its own part of the rank's slice, over the round's batches in order.
    const std::size_t part = (slice + thread_count - 1) / thread_count;
    const std::size_t begin = std::min(slice, part * t);
    const std::size_t end = std::min(slice, begin + part);
    for (std::uint64_t first = start; first < batches; first += per_round) {
      const std::uint64_t batch = first + rank * thread_count + t;
      const std::uint64_t end_of_round = std::min(batches, first + per_round);
      std::uint64_t batch_scatterings = 0;
      bool stopped = false;
      if (batch < batches) {
        stopped =
            !detail::transport_batch(walk, batch_range(photons, batches, batch), sums[t].data(),
                                     scratch, control.stop_requested, batch_scatterings);
      }
      abandoned[t] = stopped ? 1 : 0;
#pragma omp barrier
      // The master decides for the round on every rank at once, before anything is folded: a
      // batch cut short anywhere abandons the round everywhere, so that all ranks fold the same
      // batches and a stopped run holds whole batches only.
#pragma omp master
      {
        std::uint64_t flags = 0;
        if (std::find(abandoned.begin(), abandoned.end(), 1) != abandoned.end()) {
          flags |= detail::kStopFlag | detail::kAbandonFlag;
        }
        if ((control.stop_requested != nullptr && control.stop_requested->load()) ||
            failure != nullptr) {
          flags |= detail::kStopFlag;
        }
        const auto now = std::chrono::steady_clock::now();
        const CheckpointPolicy& policy = control.checkpoint;
        const bool due =
            (policy.every_batches > 0 &&
             end_of_round - last_checkpoint_batches >= policy.every_batches) ||
            (policy.every_seconds > 0.0 &&
             std::chrono::duration<double>(now - last_checkpoint).count() >= policy.every_seconds);
        if (world.is_root() && due && end_of_round < batches && control.save_checkpoint) {
          flags |= detail::kCheckpointFlag;
        }
        flags = world.bitwise_or(flags);
        const std::uint64_t held = (flags & detail::kAbandonFlag) ? done : end_of_round;
        if (flags & detail::kAbandonFlag) flags &= ~detail::kCheckpointFlag;
        // Stopping early saves the state too, so that the run can be resumed from there, unless
        // the last checkpoint (or the one resumed from) already holds it.
        if ((flags & detail::kStopFlag) && held < batches && held > last_checkpoint_batches &&
            control.save_checkpoint) {
          flags |= detail::kCheckpointFlag;
        }
        if (ranks > 1 && !(flags & detail::kAbandonFlag)) {
          // Pack [owner][thread][owner's cells], clearing the buffers for the next round.
          double* out = send.data();
          std::size_t offset = 0;
          for (const std::size_t count : slices) {
            for (std::vector<double>& buffer : sums) {
              std::copy_n(buffer.begin() + static_cast<std::ptrdiff_t>(offset), count, out);
              std::fill_n(buffer.begin() + static_cast<std::ptrdiff_t>(offset), count, 0.0);
              out += count;
            }
            offset += count;
          }
          world.all_to_all(send, send_counts, received, receive_counts);
        }
        round_flags = flags;
      }
#pragma omp barrier
      const bool folding = !(round_flags & detail::kAbandonFlag);
      if (folding) {
        scatterings[t] += batch_scatterings;
        for (std::uint64_t k = 0; k < per_round && first + k < batches; ++k) {
          const BatchRange range = batch_range(photons, batches, first + k);
          double* batch_sums = ranks > 1 ? received.data() + k * slice : sums[k].data();
          statistics.add_batch(first + k, batch_sums, static_cast<double>(range.last - range.first),
                               begin, end);
        }
        // Every thread folds (and clears) parts of every buffer: all are done before any thread
        // scores its next batch, or the master reads the state for a checkpoint.
#pragma omp barrier
      }
#pragma omp master
      {
        if (folding) {
          done = end_of_round;
          if (progress) {
            progress({done, batches, start, batch_range(photons, batches, done).first,
                      batch_range(photons, batches, start).first});
          }
        }
        if (round_flags & detail::kCheckpointFlag) {
          try {
            const RunState state = gather_state();
            if (world.is_root()) control.save_checkpoint(state);
          } catch (...) {
            failure = std::current_exception();  // stops every rank after the next round
          }
          last_checkpoint = std::chrono::steady_clock::now();
          last_checkpoint_batches = done;
        }
      }
      if (round_flags & detail::kStopFlag) break;
    }
  }

  RunState state = gather_state();
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
  outcome.threads = threads;
  outcome.ranks = ranks;
  return outcome;
}

}  // namespace scatterlab
