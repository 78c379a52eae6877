// A range check for real-valued options that also refuses NaN (CLI::Range compares with < and
// >, which NaN passes), so `--t nan` is bad usage (exit 2) like any other value out of range.
#pragma once
#include <CLI/CLI.hpp>

#include <sstream>
#include <string>

namespace dcurve::cli {

inline CLI::Validator finite_range(double min, double max) {
  std::ostringstream text;
  text << "[" << min << " - " << max << "]";
  const std::string range = text.str();
  return CLI::Validator(
      [min, max, range](std::string& text) -> std::string {
        double x = 0;
        if (!CLI::detail::lexical_cast(text, x)) return "Value " + text + " is not a number";
        if (!(x >= min && x <= max)) return "Value " + text + " not in range " + range;
        return std::string();
      },
      "FLOAT in " + range);
}

}  // namespace dcurve::cli
