#pragma once
// The timestamps depthtrack accepts, in seconds. Beyond these a timestamp is a unit mistake (nanoseconds)
// or a corrupt file (a frame id off by 1e9), not a recording: the motion model divides by the step, and
// the output would carry the nonsense on.
#include <cmath>
#include <depthtrack/error.hpp>
#include <string>

namespace depthtrack {

// About 317 years: Unix-epoch seconds (1.7e9, as ROS stamps them) pass; nanoseconds do not.
inline constexpr double kMaxAbsTimestamp = 1e10;
inline constexpr double kMaxTimeStep = 86400;  // seconds between frames: a day

// InputError naming what (e.g. "timestamp") unless t is finite and within (-kMaxAbsTimestamp, kMaxAbsTimestamp).
inline void check_timestamp(double t, const std::string& what = "timestamp") {
  if (!std::isfinite(t)) throw InputError(what + " is not finite");
  if (std::abs(t) >= kMaxAbsTimestamp)
    throw InputError(
        what + " " + std::to_string(t) +
        " s is outside the sane range (-1e10, 1e10) s: timestamps are seconds (nanoseconds divided by 1e9)");
}

}  // namespace depthtrack
