#pragma once
// A one-line progress bar with an ETA on standard error, drawn only when standard error is a
// terminal, so that logs and pipes stay clean.

#include <chrono>
#include <string>

namespace scatterlab::cli {

class ProgressBar {
 public:
  explicit ProgressBar(std::string label);
  ~ProgressBar();

  void update(double fraction_done);  // redraws at most a few times a second
  void finish();                      // clears the line

 private:
  std::string label_;
  bool enabled_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
};

}  // namespace scatterlab::cli
