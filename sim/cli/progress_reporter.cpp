#include "progress_reporter.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace scatterlab::cli {
namespace {

constexpr std::chrono::milliseconds kBarRedraw{200};
constexpr std::size_t kLineWidth = 120;

}  // namespace

ProgressReporter::ProgressReporter(std::string label, std::string unit, double log_interval_seconds)
    : label_(std::move(label)),
      unit_(std::move(unit)),
      mode_(isatty(STDERR_FILENO) == 1   ? Mode::bar
            : log_interval_seconds > 0.0 ? Mode::lines
                                         : Mode::off),
      interval_(mode_ == Mode::bar ? std::chrono::duration<double>(kBarRedraw)
                                   : std::chrono::duration<double>(log_interval_seconds)),
      start_(std::chrono::steady_clock::now()),
      last_(start_) {}

ProgressReporter::~ProgressReporter() {
  finish();
}

// Off a terminal the first line is due at once, then one per interval.
bool ProgressReporter::due(std::chrono::steady_clock::time_point now) const {
  if (mode_ == Mode::lines && !said_) return true;
  return mode_ != Mode::off && now - last_ >= interval_;
}

void ProgressReporter::start(std::uint64_t done, std::uint64_t total) {
  if (mode_ != Mode::lines) return;
  const std::string resumed = done > 0 ? fmt::format(" ({} resumed)", done) : "";
  fmt::print(stderr, "{}: {}/{} {}{}, started; a line every {:g} s\n", label_, done, total, unit_,
             resumed, interval_.count());
  std::fflush(stderr);
  said_ = true;
  last_ = std::chrono::steady_clock::now();
}

void ProgressReporter::update(std::uint64_t done, std::uint64_t total) {
  const auto now = std::chrono::steady_clock::now();
  if (!due(now)) return;
  last_ = now;
  report({done, total, 0, std::chrono::duration<double>(now - start_).count()}, "");
}

void ProgressReporter::update(const BatchProgress& progress) {
  const auto now = std::chrono::steady_clock::now();
  if (!due(now)) return;
  last_ = now;
  const double seconds = std::chrono::duration<double>(now - start_).count();
  const WorkPace photons{progress.photons_done, 0, progress.photons_resumed, seconds};
  // Events per photon say why a run is slow: a nearly conservative medium's photons take 1e5.
  const std::string events =
      progress.events_per_photon > 0.0
          ? fmt::format(", {:.3g} events/photon", progress.events_per_photon)
          : "";
  report({progress.batches_done, progress.batches, progress.batches_resumed, seconds},
         fmt::format(", {:.2g} photons/s{}", photons.units_per_second(), events));
}

void ProgressReporter::report(const WorkPace& pace, const std::string& rate) {
  const std::string resumed =
      pace.done_before > 0 ? fmt::format(" ({} resumed)", pace.done_before) : "";
  const std::string text =
      fmt::format("{}/{} {}{}{}, {} elapsed, ETA {}", pace.done, pace.total, unit_, resumed, rate,
                  duration_text(pace.seconds), duration_text(pace.seconds_left()));
  if (mode_ == Mode::lines) {
    fmt::print(stderr, "{}: {}\n", label_, text);
    said_ = true;
  } else {
    constexpr int width = 30;
    const double fraction =
        pace.total > 0 ? static_cast<double>(pace.done) / static_cast<double>(pace.total) : 0.0;
    const int filled = static_cast<int>(std::clamp(fraction, 0.0, 1.0) * width);
    fmt::print(stderr, "\r{} [{}{}] {:5.1f}%  {}   ", label_,
               std::string(static_cast<std::size_t>(filled), '#'),
               std::string(static_cast<std::size_t>(width - filled), ' '), 100.0 * fraction, text);
    drawn_ = true;
  }
  std::fflush(stderr);
}

void ProgressReporter::finish() {
  if (!drawn_) return;
  fmt::print(stderr, "\r{}\r", std::string(kLineWidth, ' '));
  std::fflush(stderr);
  drawn_ = false;
}

}  // namespace scatterlab::cli
