#pragma once
// Bad input is reported once, naming the field and what it accepts (docs/architecture.md,
// "Errors").

#include <stdexcept>
#include <string>

namespace scatterlab {

class InputError : public std::runtime_error {
 public:
  // what() reads "<field>: <problem>; accepted: <accepted>".
  InputError(const std::string& field, const std::string& problem, const std::string& accepted)
      : std::runtime_error(field + ": " + problem + "; accepted: " + accepted), field_(field) {}

  const std::string& field() const { return field_; }

 private:
  std::string field_;
};

// A command of an optional component that this build left out (CMakeLists.txt, "Optional
// components"), e.g. not_in_this_build("fit", "Ceres (Debian: libceres-dev)").
inline InputError not_in_this_build(const std::string& command, const std::string& needs) {
  return InputError(command, "this build of scatterlab has no '" + command + "' command",
                    "a build with " + needs + ": install it, then configure and build again");
}

}  // namespace scatterlab
