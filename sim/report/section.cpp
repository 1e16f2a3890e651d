#include "scatterlab/report/section.hpp"

#include <fmt/format.h>

namespace scatterlab::report {

bool Section::passed() const { return failures().empty(); }

std::size_t Section::checks_passed() const {
  std::size_t passed = 0;
  for (const Check& check : checks) passed += check.passed ? 1 : 0;
  return passed;
}

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
