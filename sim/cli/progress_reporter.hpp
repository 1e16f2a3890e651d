#pragma once
// How far a long command has got, on standard error only (standard output carries results): on a
// terminal a bar with the ETA, redrawn a few times a second and cleared at the end; off a terminal
// (batch jobs, `| tee`, cluster logs) one plain line as it starts, then one every --log-interval
// seconds, e.g.
//
//   simulate: 12/64 batches, 1.9e6 photons/s, 38.2 events/photon, 41 s elapsed, ETA 3 min
//
// Rates and the ETA count this process's work only (core/work_pace.hpp): after --resume, the
// batches done by the earlier run are neither fast nor slow. update() costs a clock read unless
// a line is due, so it may be called per batch or per tile.

#include <chrono>
#include <cstdint>
#include <string>

#include "scatterlab/core/work_pace.hpp"
#include "scatterlab/transport/batch_runner.hpp"

namespace scatterlab::cli {

class ProgressReporter {
 public:
  // `label` starts every line ("simulate"), `unit` names what is counted ("batches", "tiles");
  // `log_interval_seconds` 0 keeps the lines off a terminal off.
  ProgressReporter(std::string label, std::string unit, double log_interval_seconds);
  ~ProgressReporter();
  ProgressReporter(const ProgressReporter&) = delete;
  ProgressReporter& operator=(const ProgressReporter&) = delete;

  // Off a terminal, one line as the work starts ("simulate: 0/64 batches, started; a line every
  // 10 s"), so that a log shows at once that the job runs and how much it holds.
  void start(std::uint64_t done, std::uint64_t total);
  void update(std::uint64_t done, std::uint64_t total);
  // Batches, with photons per second and scattering events per photon.
  void update(const BatchProgress& progress);
  void finish();  // clears the bar

 private:
  bool due(std::chrono::steady_clock::time_point now) const;
  void report(const WorkPace& pace, const std::string& rate);

  enum class Mode { bar, lines, off };
  std::string label_, unit_;
  Mode mode_;
  std::chrono::duration<double> interval_;
  std::chrono::steady_clock::time_point start_, last_;
  bool drawn_ = false;  // a bar is on the terminal
  bool said_ = false;   // a line is in the log
};

}  // namespace scatterlab::cli
