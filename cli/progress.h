// A one-line progress bar on stderr, shown only when stderr and stdout are terminals, so
// piped or --json output stays clean.
#pragma once
#include <functional>
#include <string>

namespace dcurve::cli {

// Returns a callback taking the fraction done in [0, 1], or an empty function when not on
// a terminal. The bar shows the time left at the pace so far and finishes its line when
// the fraction reaches 1.
std::function<void(double)> progress_bar(const std::string& label);

}  // namespace dcurve::cli
