// The batch scheduler (batch_runner.hpp): one class for every kernel, in named stages:
//   resume      the root's saved state, dealt out to the ranks slice by slice;
//   deal        the next group of batches to a free thread (a shared counter);
//   transport   one batch into a ring buffer, slice by slice, stopping when asked;
//   fold        complete groups into the statistics, strictly in order, in parts that waiting
//               threads share;
//   exchange    with several ranks, a group's sums to the ranks that own their cells;
//   checkpoint  the whole state gathered on the root and saved, when due or when stopping.
#include "scatterlab/transport/batch_runner.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "scatterlab/core/error.hpp"
#include "scatterlab/tally/batch_statistics.hpp"
#include "scatterlab/transport/communicator.hpp"

namespace scatterlab {

int batch_threads(const RunSettings& run) {
  const int asked = run.threads > 0 ? run.threads : omp_get_max_threads();
  return static_cast<int>(std::min<std::uint64_t>(run.batches, static_cast<std::uint64_t>(asked)));
}

std::size_t score_buffers(int threads, std::uint64_t batches, int ranks) {
  const auto per_rank = static_cast<std::uint64_t>(ranks);
  const std::uint64_t groups = (batches + per_rank - 1) / per_rank;
  const std::uint64_t ring = 2 * static_cast<std::uint64_t>(threads) - 1;
  return static_cast<std::size_t>(std::max<std::uint64_t>(1, std::min(ring, groups)));
}

MemoryEstimate batch_memory(std::size_t cells, int threads, std::uint64_t batches, int ranks,
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

namespace {

// Rank p owns cells [cells * p / ranks, cells * (p + 1) / ranks).
std::vector<std::size_t> cell_slices(std::size_t cells, int ranks) {
  std::vector<std::size_t> counts(static_cast<std::size_t>(ranks));
  const auto r = static_cast<std::size_t>(ranks);
  for (std::size_t p = 0; p < r; ++p) counts[p] = cells * (p + 1) / r - cells * p / r;
  return counts;
}

// A group's flags, combined across ranks before it is folded.
constexpr std::uint64_t kStopFlag = 1, kCheckpointFlag = 2, kAbandonFlag = 4;

// One buffer of the ring: the group whose batch it last received (none yet: ~0), whether that
// batch was whole or cut short, and its scattering events.
struct RingSlot {
  std::uint64_t group = ~std::uint64_t{0};
  bool whole = false;
  std::uint64_t scatterings = 0;
};

static_assert(detail::kFoldPart % BatchStatistics::kBlock == 0,
              "parts folded at once share no block");

// A batch being folded in parts of detail::kFoldPart cells.
struct FoldJob {
  double* sums = nullptr;
  std::uint64_t batch = 0;
  double photons = 0.0;
  std::size_t parts = 0;
};

class BatchScheduler {
 public:
  BatchScheduler(const RunSettings& run, std::size_t cells, const SliceKernel& kernel,
                 const ProgressCallback& progress, const RunControl& control, Communicator& world)
      : kernel_(kernel),
        progress_(progress),
        control_(control),
        world_(world),
        ranks_(world.size()),
        rank_(static_cast<std::size_t>(world.rank())),
        rank_count_(static_cast<std::uint64_t>(ranks_)),
        photons_(run.photons),
        batches_(run.batches),
        cells_(cells),
        // Every rank uses the root's thread count, so that all hold rings of the same size.
        threads_(static_cast<int>(
            world.broadcast_from_root(static_cast<std::uint64_t>(batch_threads(run))))),
        slices_(cell_slices(cells, ranks_)),
        slice_(slices_[rank_]),
        statistics_(0),
        clock_start_(std::chrono::steady_clock::now()) {
    resume();
    groups_ = (batches_ - start_ + rank_count_ - 1) / rank_count_;
    slots_ = score_buffers(threads_, batches_ - start_, ranks_);
    ring_.resize(slots_);
    ring_state_.resize(slots_);
    // A buffer holds the cells in owner order, so it is sent as it is: slices[p] values to p.
    if (ranks_ > 1) {
      received_.resize(rank_count_ * slice_);
      receive_counts_.assign(static_cast<std::size_t>(ranks_), slice_);
    }
    last_checkpoint_ = clock_start_;
    last_checkpoint_batches_ = start_;
    done_ = start_;
  }

  BatchOutcome run() {
#pragma omp parallel num_threads(threads_)
    work(static_cast<std::size_t>(omp_get_thread_num()),
         static_cast<std::size_t>(omp_get_num_threads()));
    report_progress();
    return outcome();
  }

 private:
  // --- resume -----------------------------------------------------------------------------------

  // The root's saved state, dealt out slice by slice. Whether it fits this run is checked on the
  // root and agreed by all ranks, so that a refusal ends every rank rather than leaving the
  // others waiting for the root.
  void resume() {
    const RunState* resume = world_.is_root() ? control_.resume_from : nullptr;
    std::string misfit;
    if (resume != nullptr && (resume->mean.size() != cells_ || resume->squares.size() != cells_)) {
      misfit = fmt::format("holds {} values per Welford array but this run's tallies have {} cells",
                           resume->mean.size(), cells_);
    } else if (resume != nullptr && resume->batches_folded > batches_) {
      misfit = fmt::format("has folded {} batches but this run has {}", resume->batches_folded,
                           batches_);
    }
    if (world_.broadcast_from_root(misfit.empty() ? 0 : 1) != 0) {
      throw InputError("--resume",
                       fmt::format("the checkpoint '{}' {}", control_.resume_source,
                                   misfit.empty() ? "does not fit this run (see rank 0)" : misfit),
                       "a checkpoint written by this run (same parameters and seed)");
    }
    start_ = world_.broadcast_from_root(resume ? resume->batches_folded : 0);
    statistics_ = BatchStatistics(slice_);
    if (start_ > 0) {
      std::vector<double> mean = world_.scatter_from_root(
          resume ? std::span<const double>(resume->mean) : std::span<const double>(), slices_);
      std::vector<double> squares = world_.scatter_from_root(
          resume ? std::span<const double>(resume->squares) : std::span<const double>(), slices_);
      statistics_ = BatchStatistics(std::move(mean), std::move(squares));
    }
    scatterings_ = resume != nullptr ? resume->scattering_events : 0;
    resumed_wall_seconds_ = resume != nullptr ? resume->wall_seconds : 0.0;
  }

  // --- deal and transport: each thread of the team --------------------------------------------

  // Thread t of a team of `team` (OpenMP may grant fewer threads than asked: the team shares the
  // work by its own size). A thread that cannot work keeps its failure and hands in the group it
  // takes cut short, so that every rank stops after the whole groups before it; the failure is
  // thrown once the threads have left the region, where an exception may pass.
  void work(std::size_t t, std::size_t team) {
    if (t == 0) granted_ = static_cast<int>(team);
    // Each thread first touches its own share of the ring.
    try {
      for (std::size_t s = t; s < slots_; s += team) ring_[s].assign(cells_, 0.0);
    } catch (...) {
      keep_failure(std::current_exception());
      ring_failed_ = true;
    }
#pragma omp barrier
    std::unique_ptr<SliceKernel::Worker> worker;
    try {
      if (!ring_failed_) worker = kernel_.start_worker();
    } catch (...) {
      keep_failure(std::current_exception());
    }
    for (;;) {
      const std::uint64_t g = next_group_.fetch_add(1);  // deal
      if (g >= groups_) {
        wait_helping([&] { return next_to_fold_ >= groups_; });  // help fold the last batches
        break;
      }
      wait_helping([&] { return g < next_to_fold_ + slots_; });
      if (halted_) break;
      const std::uint64_t batch = start_ + g * rank_count_ + rank_;
      std::uint64_t batch_scatterings = 0;
      bool whole = worker != nullptr;
      const auto walk_start = std::chrono::steady_clock::now();
      if (worker && batch < batches_) {
        try {
          whole = transport(*worker, batch_range(photons_, batches_, batch), ring_[g % slots_].data(),
                            batch_scatterings);
        } catch (...) {
          keep_failure(std::current_exception());
          worker.reset();
          whole = false;
        }
      }
      const std::chrono::duration<double> walked = std::chrono::steady_clock::now() - walk_start;
      {
        std::lock_guard<std::mutex> lock(ring_mutex_);
        ring_state_[g % slots_] = {g, whole, batch_scatterings};
        walk_seconds_ += walked.count();
        walk_events_ += batch_scatterings;
      }
      fold_ready();
      if (t == 0) report_progress();
      if (!worker) break;
    }
  }

  void keep_failure(std::exception_ptr error) {
    std::lock_guard<std::mutex> lock(thread_failure_mutex_);
    if (!thread_failure_) thread_failure_ = std::move(error);
  }

  // One batch into `sums` in slices of kStopPollPhotons photons, in photon order (the same
  // arithmetic as one call, so the same bits). False when a stop was requested (from outside,
  // or by the scheduler once it has decided to end) before the batch was complete: its sums are
  // then partial and must not be folded.
  bool transport(SliceKernel::Worker& worker, BatchRange range, double* sums,
                 std::uint64_t& scatterings) {
    const std::atomic<bool>* stop_requested = control_.stop_requested;
    for (std::uint64_t first = range.first; first < range.last;
         first += detail::kStopPollPhotons) {
      if ((stop_requested != nullptr && stop_requested->load(std::memory_order_relaxed)) ||
          halted_.load(std::memory_order_relaxed)) {
        return false;
      }
      const std::uint64_t last = std::min(range.last, first + detail::kStopPollPhotons);
      scatterings += worker.run(first, last, sums);
    }
    return true;
  }

  // --- fold --------------------------------------------------------------------------------------

  // Folds every group that is next in order and complete, unless another thread is folding:
  // that one looks again after it lets go, so that a group completed meanwhile is never left
  // behind and every complete group is folded before the threads leave the parallel region.
  void fold_ready() {
    auto next_is_complete = [&] {
      return !halted_ && next_to_fold_ < groups_ &&
             ring_state_[next_to_fold_ % slots_].group == next_to_fold_;
    };
    for (;;) {
      std::unique_lock<std::mutex> folding(fold_mutex_, std::try_to_lock);
      if (!folding.owns_lock()) return;
      for (;;) {
        RingSlot slot;
        {
          std::lock_guard<std::mutex> lock(ring_mutex_);
          if (!next_is_complete()) break;
          slot = ring_state_[next_to_fold_ % slots_];
        }
        fold_group(slot.group, slot.whole, slot.scatterings, ring_[slot.group % slots_]);
        {
          std::lock_guard<std::mutex> lock(ring_mutex_);
          ++next_to_fold_;
        }
        buffer_freed_.notify_all();
      }
      folding.unlock();
      std::lock_guard<std::mutex> lock(ring_mutex_);
      if (!next_is_complete()) return;
    }
  }

  // Folds group g, whose batch on this rank is in `sums` (`whole`, or cut short by a stop).
  // Every rank folds the same groups in the same order: the flags are combined first, so that a
  // batch cut short anywhere abandons the group everywhere. Under fold_mutex_.
  void fold_group(std::uint64_t g, bool whole, std::uint64_t batch_scatterings,
                  std::vector<double>& sums) {
    const std::uint64_t first = start_ + g * rank_count_;
    const std::uint64_t end_of_group = std::min(batches_, first + rank_count_);
    std::uint64_t flags = group_flags(whole, end_of_group);
    const bool abandon = (flags & kAbandonFlag) != 0;
    if (abandon) flags &= ~kCheckpointFlag;
    // Stopping early saves the state too, so that the run can be resumed from there, unless the
    // last checkpoint (or the one resumed from) already holds it.
    const std::uint64_t held = abandon ? done_ : end_of_group;
    if ((flags & kStopFlag) && held < batches_ && held > last_checkpoint_batches_ &&
        control_.save_checkpoint) {
      flags |= kCheckpointFlag;
    }
    if (!abandon) {
      double* group_sums = exchange(sums);
      for (std::uint64_t b = first; b < end_of_group; ++b) {
        fold_batch(b, group_sums + (b - first) * slice_);
      }
      scatterings_ += batch_scatterings;
      // This rank's own batch of the group, for the events per photon of the progress line.
      if (const std::uint64_t own = first + rank_; own < end_of_group) {
        const BatchRange range = batch_range(photons_, batches_, own);
        own_photons_ += range.last - range.first;
        own_events_ += batch_scatterings;
      }
      done_ = end_of_group;
      std::lock_guard<std::mutex> lock(progress_mutex_);
      latest_ = {done_,
                 batches_,
                 start_,
                 batch_range(photons_, batches_, done_).first,
                 batch_range(photons_, batches_, start_).first,
                 own_photons_ > 0 ? static_cast<double>(own_events_) /
                                        static_cast<double>(own_photons_)
                                  : 0.0};
      unreported_ = true;
    }
    if (flags & kCheckpointFlag) checkpoint();
    if (flags & kStopFlag) {
      std::lock_guard<std::mutex> lock(ring_mutex_);
      halted_ = true;
    }
  }

  // The group's flags, combined across ranks: stop and abandon for a batch cut short (a stop
  // request shows as one: every batch in flight is cut short, and any taken after it is cut before
  // its first photon, so the whole batches before it are still folded), stop after a failed
  // checkpoint, and a checkpoint when one is due.
  std::uint64_t group_flags(bool whole, std::uint64_t end_of_group) {
    std::uint64_t flags = 0;
    if (!whole) flags |= kStopFlag | kAbandonFlag;
    if (checkpoint_failure_ != nullptr) flags |= kStopFlag;
    const auto now = std::chrono::steady_clock::now();
    const CheckpointPolicy& policy = control_.checkpoint;
    const bool due =
        (policy.every_batches > 0 &&
         end_of_group - last_checkpoint_batches_ >= policy.every_batches) ||
        (policy.every_seconds > 0.0 &&
         std::chrono::duration<double>(now - last_checkpoint_).count() >= policy.every_seconds);
    if (world_.is_root() && due && end_of_group < batches_ && control_.save_checkpoint) {
      flags |= kCheckpointFlag;
    }
    return world_.bitwise_or(flags);
  }

  // Folds batch b's sums into the statistics, with the help of any thread that is waiting.
  void fold_batch(std::uint64_t b, double* sums) {
    const BatchRange range = batch_range(photons_, batches_, b);
    const auto batch_photons = static_cast<double>(range.last - range.first);
    const std::size_t parts = (slice_ + detail::kFoldPart - 1) / detail::kFoldPart;
    if (threads_ == 1 || parts < 2) {
      statistics_.add_batch(b, sums, batch_photons, 0, slice_);
      return;
    }
    const FoldJob work{sums, b, batch_photons, parts};
    std::uint64_t generation = 0;
    {
      std::lock_guard<std::mutex> lock(ring_mutex_);
      generation = ++job_generation_;
      job_ = work;
      job_done_ = 0;
      job_next_ = (generation & 0xffffffffu) << 32;
    }
    buffer_freed_.notify_all();
    fold_parts(work, generation);
    while (job_done_.load() < parts) std::this_thread::yield();  // parts others took
  }

  // Folds the parts of `work` (generation `generation`) that no thread has taken yet. The next
  // part to take is tagged with the generation in its high 32 bits, so that a thread holding an
  // earlier job's copy takes nothing.
  void fold_parts(const FoldJob& work, std::uint64_t generation) {
    const std::uint64_t tag = (generation & 0xffffffffu) << 32;
    for (;;) {
      std::uint64_t next = job_next_.load();
      do {
        if ((next & ~std::uint64_t{0xffffffffu}) != tag || (next & 0xffffffffu) >= work.parts) {
          return;
        }
      } while (!job_next_.compare_exchange_weak(next, next + 1));
      const std::size_t begin = static_cast<std::size_t>(next & 0xffffffffu) * detail::kFoldPart;
      statistics_.add_batch(work.batch, work.sums, work.photons, begin,
                            std::min(slice_, begin + detail::kFoldPart));
      job_done_.fetch_add(1);
    }
  }

  // Waits under ring_mutex_ until ready() or the run halts, folding parts of the batch being
  // folded meanwhile.
  template <class Ready>
  void wait_helping(Ready ready) {
    std::unique_lock<std::mutex> lock(ring_mutex_);
    const auto parts_left = [&] { return (job_next_.load() & 0xffffffffu) < job_.parts; };
    for (;;) {
      buffer_freed_.wait(lock, [&] { return ready() || halted_ || parts_left(); });
      if (ready() || halted_) return;
      const FoldJob work = job_;
      const std::uint64_t generation = job_generation_;
      lock.unlock();
      fold_parts(work, generation);
      lock.lock();
    }
  }

  // --- exchange ----------------------------------------------------------------------------------

  // This rank's sums of every batch of a group, slice by slice in batch order: its own buffer
  // with one rank; with several, the buffer goes out in the owners' slices (and is cleared for
  // its next batch) and back come this rank's slices of every batch of the group, in rank order.
  double* exchange(std::vector<double>& sums) {
    if (ranks_ == 1) return sums.data();
    world_.all_to_all(sums, slices_, received_, receive_counts_);
    std::fill(sums.begin(), sums.end(), 0.0);
    return received_.data();
  }

  // --- checkpoint --------------------------------------------------------------------------------

  // The whole state, gathered on the root (a collective: every rank calls it).
  RunState gather_state() {
    RunState state;
    state.batches_folded = done_;
    state.scattering_events = world_.sum(scatterings_);
    state.wall_seconds = resumed_wall_seconds_ + std::chrono::duration<double>(
                                                     std::chrono::steady_clock::now() -
                                                     clock_start_)
                                                     .count();
    state.mean = world_.gather_to_root(statistics_.mean(), slices_);
    state.squares = world_.gather_to_root(statistics_.squares(), slices_);
    return state;
  }

  // A failure to save stops every rank after the next group.
  void checkpoint() {
    try {
      const RunState saved = gather_state();
      if (world_.is_root()) control_.save_checkpoint(saved);
    } catch (...) {
      checkpoint_failure_ = std::current_exception();
    }
    last_checkpoint_ = std::chrono::steady_clock::now();
    last_checkpoint_batches_ = done_;
  }

  // --- the caller's view -------------------------------------------------------------------------

  // The latest folded state, for the calling thread to report (ProgressCallback).
  void report_progress() {
    if (!progress_) return;
    BatchProgress now;
    {
      std::lock_guard<std::mutex> lock(progress_mutex_);
      if (!unreported_) return;
      now = latest_;
      unreported_ = false;
    }
    progress_(now);
  }

  BatchOutcome outcome() {
    RunState state = gather_state();
    if (thread_failure_) std::rethrow_exception(thread_failure_);
    if (checkpoint_failure_) std::rethrow_exception(checkpoint_failure_);
    BatchOutcome outcome;
    outcome.batches_done = done_;
    outcome.photons_done = batch_range(photons_, batches_, done_).first;  // before batch done_
    outcome.standard_error = BatchStatistics::standard_error_from_squares(state.squares, done_);
    if (!world_.is_root()) outcome.standard_error.clear();
    outcome.mean = std::move(state.mean);
    outcome.scattering_events = state.scattering_events;
    outcome.batches_resumed = start_;
    outcome.photons_resumed = batch_range(photons_, batches_, start_).first;
    outcome.resumed_wall_seconds = resumed_wall_seconds_;
    outcome.walk_seconds = walk_seconds_;
    outcome.walk_events = walk_events_;
    outcome.threads = granted_;
    outcome.threads_asked = threads_;
    outcome.ranks = ranks_;
    return outcome;
  }

  // The run, fixed at the start.
  const SliceKernel& kernel_;
  const ProgressCallback& progress_;
  const RunControl& control_;
  Communicator& world_;
  const int ranks_;
  const std::size_t rank_;
  const std::uint64_t rank_count_;
  const std::uint64_t photons_, batches_;
  const std::size_t cells_;
  const int threads_;
  const std::vector<std::size_t> slices_;
  const std::size_t slice_;  // this rank's cells
  std::uint64_t start_ = 0;  // batches folded before this process (a resumed run)
  std::uint64_t groups_ = 0;
  std::size_t slots_ = 0;

  // The ring of score buffers. Under ring_mutex_: the slots' states, the next group to fold (a
  // group's buffer is free once it is folded), halted_ once the run ends early (no thread takes
  // or finishes another batch), and the batch being folded in parts (its job and generation).
  std::vector<std::vector<double>> ring_;
  std::vector<RingSlot> ring_state_;
  std::atomic<std::uint64_t> next_group_{0};
  std::atomic<bool> halted_{false};
  std::mutex ring_mutex_;
  std::condition_variable buffer_freed_;
  std::uint64_t next_to_fold_ = 0;
  FoldJob job_;
  std::uint64_t job_generation_ = 0;
  std::atomic<std::uint64_t> job_next_{0};
  std::atomic<std::size_t> job_done_{0};

  // Held by the thread that folds; everything below it is touched under fold_mutex_ only (or on
  // the calling thread before and after the parallel region).
  std::mutex fold_mutex_;
  BatchStatistics statistics_;
  std::vector<double> received_;  // a group's slices from every rank
  std::vector<std::size_t> receive_counts_;
  std::uint64_t scatterings_ = 0;
  std::uint64_t own_photons_ = 0, own_events_ = 0;  // this rank's batches folded by this process
  // This process's time in the walk, summed over threads, and its events (ring_mutex_).
  double walk_seconds_ = 0.0;
  std::uint64_t walk_events_ = 0;
  const std::chrono::steady_clock::time_point clock_start_;
  double resumed_wall_seconds_ = 0.0;
  std::chrono::steady_clock::time_point last_checkpoint_;
  std::uint64_t last_checkpoint_batches_ = 0;
  std::uint64_t done_ = 0;
  std::exception_ptr checkpoint_failure_;

  // The team: what OpenMP granted, and the first failure of a thread that could not work.
  std::atomic<int> granted_{1};
  std::atomic<bool> ring_failed_{false};
  std::mutex thread_failure_mutex_;
  std::exception_ptr thread_failure_;

  // The latest folded state, for the calling thread to report.
  std::mutex progress_mutex_;
  BatchProgress latest_;
  bool unreported_ = false;
};

}  // namespace

BatchOutcome run_batches(const RunSettings& run, std::size_t cells, const SliceKernel& kernel,
                         const ProgressCallback& progress, const RunControl& control) {
  SerialCommunicator serial;
  Communicator& world = control.communicator != nullptr ? *control.communicator : serial;
  BatchScheduler scheduler(run, cells, kernel, progress, control, world);
  return scheduler.run();
}

}  // namespace scatterlab
