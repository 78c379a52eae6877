// The one rule for frame times an input file states (glTF key times, MDD frame times): they
// give the frame rate only when they are finite, strictly increasing, evenly spaced and at a
// rate the command line itself accepts; anything else is refused, never resampled or guessed.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

namespace dcurve {

// The range of `encode --fps`, and of any rate read from a file.
constexpr double kMinFrameRate = 1e-3, kMaxFrameRate = 1e6;

// Frames per second of `times` (seconds). Each time may differ from the even spacing by 1% of
// the spacing (plus the float rounding of its own value). One time gives no rate (*fps left
// as it is). `what` names the times in errors ("the weights animation's key times").
bool frame_rate_from_times(const std::vector<double>& times, const std::string& what, double* fps, std::string* error);

// Whether a clip of `frame_count` frames at `fps` may start at `start` seconds (PLAC's
// start_time): the float32 key times an output writes (glTF, MDD) must be finite and pass
// frame_rate_from_times, so that dcurve reads back what it wrote. `what` names the source.
bool check_start_time(double start, double fps, size_t frame_count, const std::string& what, std::string* error);

}  // namespace dcurve
