// dcurve.Error: what the module raises for bad input, a ValueError carrying the message the
// CLI prints for the same problem (without the "dcurve <command>: " prefix).
#pragma once
#include <stdexcept>
#include <string>

namespace dcurve::python {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace dcurve::python
