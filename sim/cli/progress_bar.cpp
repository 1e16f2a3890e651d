#include "progress_bar.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace scatterlab::cli {

ProgressBar::ProgressBar(std::string label)
    : label_(std::move(label)),
      enabled_(isatty(STDERR_FILENO) == 1),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {}

ProgressBar::~ProgressBar() {
  finish();
}

void ProgressBar::update(double fraction_done) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (drawn_ && fraction_done < 1.0 && now - last_draw_ < std::chrono::milliseconds(200)) return;
  last_draw_ = now;
  drawn_ = true;
  const double done = std::clamp(fraction_done, 0.0, 1.0);
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const std::string eta =
      done > 0.0 ? fmt::format("ETA {:.0f} s", elapsed * (1.0 - done) / done) : "ETA --";
  constexpr int width = 30;
  const int filled = static_cast<int>(done * width);
  fmt::print(stderr, "\r{} [{}{}] {:5.1f}%  {:.0f} s elapsed, {}   ", label_,
             std::string(static_cast<std::size_t>(filled), '#'),
             std::string(static_cast<std::size_t>(width - filled), ' '), 100.0 * done, elapsed,
             eta);
  std::fflush(stderr);
}

void ProgressBar::finish() {
  if (!enabled_ || !drawn_) return;
  fmt::print(stderr, "\r{}\r", std::string(100, ' '));
  std::fflush(stderr);
  drawn_ = false;
}

}  // namespace scatterlab::cli
