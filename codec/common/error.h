// The project's error convention: functions return false and, when the caller passed a
// string, describe the problem in it.
#pragma once
#include <string>

namespace dcurve {

// Stores `message` in *error (when error is not null) and returns false.
inline bool fail(std::string* error, const std::string& message) {
  if (error) *error = message;
  return false;
}

}  // namespace dcurve
