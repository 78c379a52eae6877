// Progress of a long step on stderr. On a terminal: a one-line bar redrawn in place. Anywhere
// else (a pipe, a log file, a farm job, CI): one plain line every few seconds with the stage,
// the percent done and the time left, so a log shows the job is alive without a stream of
// carriage returns. stdout is never written, so piped or --json output stays clean.
#pragma once
#include <functional>
#include <string>

namespace dcurve::cli {

// Seconds between two lines when stderr is not a terminal. The environment variable
// DCURVE_PROGRESS_INTERVAL (seconds, > 0) overrides it, for tests.
constexpr double kProgressLineSeconds = 5.0;

// Returns a callback taking the fraction done in [0, 1]. `label` names the stage; lines
// start with `prefix` (e.g. "dcurve encode: "). The time left is extrapolated from the pace
// so far. The bar finishes its line when the fraction reaches 1; the lines stop there, with a
// last line only if an earlier one was printed. The callback may be called from any thread.
std::function<void(double)> progress_bar(const std::string& label, const std::string& prefix = "");

}  // namespace dcurve::cli
