#pragma once
// The field an InputError names, for tests of what a check refuses.

#include <string>

#include "scatterlab/core/error.hpp"

namespace scatterlab::test_support {

// The field of the InputError `action` throws, or "" when it throws none.
template <typename Action>
std::string field_of(Action&& action) {
  try {
    action();
  } catch (const InputError& e) {
    return e.field();
  }
  return "";
}

}  // namespace scatterlab::test_support
