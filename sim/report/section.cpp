#include "scatterlab/report/section.hpp"

#include <fmt/format.h>

namespace scatterlab::report {

bool Section::passed() const { return failures().empty(); }

std::vector<std::string> Section::failures() const {
  std::vector<std::string> failed;
  for (const Check& check : checks) {
    if (!check.passed) failed.push_back(check.what);
  }
  if (non_finite_values != 0) {
    failed.push_back(fmt::format("{} NaN or Inf values in the results", non_finite_values));
  }
  return failed;
}

}  // namespace scatterlab::report
