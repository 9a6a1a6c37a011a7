#pragma once
// Per-frame random streams of the synthesizer. The variates are drawn with explicit formulas, not
// std:: distributions, whose output differs between standard libraries: a (seed, frame) pair then
// gives the same image everywhere.
#include <cmath>
#include <cstdint>
#include <random>

namespace depthtrack::synth {

// SplitMix64 finalizer: spreads nearby seeds (1, 2, 3, ...) over the whole 64-bit range.
inline uint64_t mix64(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// The generator of one frame: any frame can be made alone, in any order, with the same result.
inline std::mt19937_64 frame_rng(uint64_t seed, int frame) {
  return std::mt19937_64(mix64(mix64(seed) ^ static_cast<uint64_t>(frame)));
}

// Uniform in [0, 1) from the top 53 bits.
inline double uniform01(std::mt19937_64& rng) {
  return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

// Two uniforms in [0, 1) from one draw (32 bits each): ample for dropout decisions, half the draws.
struct UniformPair {
  double first, second;
};
inline UniformPair uniform_pair(std::mt19937_64& rng) {
  const uint64_t bits = rng();
  return {static_cast<double>(bits >> 32) * 0x1.0p-32, static_cast<double>(bits & 0xFFFFFFFFull) * 0x1.0p-32};
}

// Standard normal variates by Marsaglia's polar method: two per accepted pair, no trigonometry.
class StandardNormal {
 public:
  double operator()(std::mt19937_64& rng) {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    double x, y, s;
    do {
      x = 2.0 * uniform01(rng) - 1.0;
      y = 2.0 * uniform01(rng) - 1.0;
      s = x * x + y * y;
    } while (s >= 1.0 || s == 0.0);
    const double scale = std::sqrt(-2.0 * std::log(s) / s);
    spare_ = y * scale;
    has_spare_ = true;
    return x * scale;
  }

 private:
  double spare_ = 0;
  bool has_spare_ = false;
};

}  // namespace depthtrack::synth
