#include "log_interval_option.hpp"

#include <cmath>
#include <cstdlib>
#include <string>

#include "value_checks.hpp"

namespace scatterlab::cli {

std::shared_ptr<double> add_log_interval_option(CLI::App& command) {
  // Ten seconds: a job shows it is alive soon after it starts; a day's log is still 8640 lines.
  auto seconds = std::make_shared<double>(10.0);
  // A bad value is a parse error: one line naming the flag, status 2, before any work (CLI11
  // names the flag).
  const CLI::Validator non_negative(
      [](std::string& text) {
        const bool number = numeric_value_problem(text, "FLOAT").empty();
        const double value = number ? std::strtod(text.c_str(), nullptr) : -1.0;
        return value >= 0.0 && std::isfinite(value)
                   ? std::string()
                   : "got \"" + text + "\"; accepted: a number of seconds >= 0 (0: no lines)";
      },
      "");
  command
      .add_option("--log-interval", *seconds,
                  "Off a terminal (batch jobs, | tee, cluster logs), write a progress line to "
                  "standard error as it starts and then every SECONDS: work done, rate and ETA; 0 "
                  "writes none. On a "
                  "terminal a progress bar is drawn instead")
      ->type_name("SECONDS")
      ->check(non_negative);
  return seconds;
}

}  // namespace scatterlab::cli
