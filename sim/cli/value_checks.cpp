#include "value_checks.hpp"

#include <fmt/format.h>

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <string_view>

#include "scatterlab/core/error.hpp"

namespace scatterlab::cli {
namespace {

bool is_digit(char c) {
  return c >= '0' && c <= '9';
}

// Decimal digits after an optional sign (no '-' when unsigned), without a leading zero.
bool is_decimal_integer(std::string_view text, bool is_unsigned) {
  if (!text.empty() && (text.front() == '+' || (!is_unsigned && text.front() == '-'))) {
    text.remove_prefix(1);
  }
  if (text.empty()) return false;
  for (const char c : text) {
    if (!is_digit(c)) return false;
  }
  return text.size() == 1 || text.front() != '0';
}

std::string quoted(const std::string& text) {
  return fmt::format("\"{}\"", text);
}

}  // namespace

std::string numeric_value_problem(const std::string& text, const std::string& type) {
  if (type == "FLOAT") {
    const std::string accepted = "a decimal number such as 0.5, 1e7 or inf";
    if (text.empty()) return "empty value; accepted: " + accepted;
    errno = 0;
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    const bool overflow = errno == ERANGE && std::isinf(value);
    if (end != text.c_str() + text.size() || std::isspace(static_cast<unsigned char>(text[0]))) {
      return fmt::format("got {}, not a number; accepted: {}", quoted(text), accepted);
    }
    if (std::isnan(value)) return fmt::format("got {}; accepted: {}", quoted(text), accepted);
    if (overflow) {
      return fmt::format("got {}, beyond the largest double (1.8e308); accepted: {}", text,
                         accepted);
    }
    return "";
  }
  const bool is_unsigned = type == "UINT";
  if (is_unsigned || type == "INT") {
    const std::string accepted =
        is_unsigned ? "a whole number >= 0 in decimal digits, without leading zeros"
                    : "a whole number in decimal digits, without leading zeros";
    if (text.empty()) return "empty value; accepted: " + accepted;
    if (!is_decimal_integer(text, is_unsigned)) {
      return fmt::format("got {}; accepted: {}", quoted(text), accepted);
    }
    // strtoull and strtoll saturate: 2^64 would be read as 2^64 - 1.
    errno = 0;
    if (is_unsigned) {
      (void)std::strtoull(text.c_str(), nullptr, 10);
    } else {
      (void)std::strtoll(text.c_str(), nullptr, 10);
    }
    if (errno == ERANGE) {
      return fmt::format("got {}, beyond a 64-bit integer; accepted: {}", text, accepted);
    }
  }
  return "";
}

void check_numeric_values(CLI::App& app) {
  for (CLI::Option* option : app.get_options()) {
    // Read before any check is added: CLI11 appends a validator's description to the name.
    std::string type = option->get_type_name();
    type = type.substr(0, type.find(':'));
    if (type != "FLOAT" && type != "INT" && type != "UINT") continue;
    option->check(CLI::Validator(
        [type](std::string& text) { return numeric_value_problem(text, type); }, ""));
  }
  for (CLI::App* command : app.get_subcommands([](CLI::App*) { return true; })) {
    check_numeric_values(*command);
  }
}

}  // namespace scatterlab::cli
