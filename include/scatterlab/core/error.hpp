#pragma once
// Bad input is reported once, naming the field and what it accepts (docs/architecture.md, "Errors").

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

}  // namespace scatterlab
