#pragma once
// Host wall-clock timing of the tracker's steps, in milliseconds.
#include <chrono>

namespace depthtrack {

class Stopwatch {
 public:
  // Milliseconds since construction or the previous lap; starts the next lap.
  double lap_ms() {
    const auto now = std::chrono::steady_clock::now();
    const double ms = std::chrono::duration<double, std::milli>(now - lap_start_).count();
    lap_start_ = now;
    return ms;
  }
  // Milliseconds since construction.
  double elapsed_ms() const {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now(), lap_start_ = start_;
};

}  // namespace depthtrack
