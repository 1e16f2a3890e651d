#pragma once
// Runs a check once per instruction set that Highway compiled and this machine runs, so that a
// kernel dispatched at run time is tested on each, not only on the best.
#include <gtest/gtest.h>
#include <hwy/targets.h>

#include <cstdint>

namespace scatterlab::testing {

template <class Check>
void on_every_target(const Check& check) {
  for (const std::int64_t target : hwy::SupportedAndGeneratedTargets()) {
    SCOPED_TRACE(hwy::TargetName(target));
    hwy::SetSupportedTargetsForTest(target);
    check();
  }
  hwy::SetSupportedTargetsForTest(0);  // back to the best the machine has
}

}  // namespace scatterlab::testing
