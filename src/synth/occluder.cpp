#include "synth/occluder.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

namespace depthtrack::synth {

namespace {
constexpr double kGapToObject = 0.12;  // metres the bar stands in front of the object's nearest point
constexpr double kNearestBar = 0.3;    // metres: never closer than this to the camera
constexpr int kRowMargin = 10;         // pixels the bar reaches beyond the object's top and bottom

struct Footprint {
  std::vector<double> columns_before;  // [k]: share of object pixels in columns < k, k = 0..width
  int top = 0, bottom = -1;
  float nearest = 0;
  long pixels = 0;
};

Footprint footprint(std::span<const float> object, int width, int height) {
  Footprint f;
  std::vector<long> per_column(static_cast<size_t>(width), 0);
  f.top = height;
  f.nearest = std::numeric_limits<float>::max();
  for (int v = 0; v < height; ++v)
    for (int u = 0; u < width; ++u) {
      const float z = object[static_cast<size_t>(v) * static_cast<size_t>(width) + static_cast<size_t>(u)];
      if (z <= 0.0f) continue;
      ++per_column[static_cast<size_t>(u)];
      f.top = std::min(f.top, v);
      f.bottom = std::max(f.bottom, v);
      f.nearest = std::min(f.nearest, z);
      ++f.pixels;
    }
  f.columns_before.assign(static_cast<size_t>(width) + 1, 0.0);
  long running = 0;
  for (int u = 0; u < width; ++u) {
    running += per_column[static_cast<size_t>(u)];
    f.columns_before[static_cast<size_t>(u) + 1] =
        f.pixels ? static_cast<double>(running) / static_cast<double>(f.pixels) : 0.0;
  }
  return f;
}

// Column boundary whose cumulative share is nearest to target, searched in [from, to]. Ties go to the
// boundary nearest the object (latest for a start, earliest for an end) so the bar wastes no columns.
int nearest_boundary(const std::vector<double>& before, double target, int from, int to, bool latest) {
  int best = from;
  for (int k = from; k <= to; ++k) {
    const double d = std::abs(before[static_cast<size_t>(k)] - target),
                 best_d = std::abs(before[static_cast<size_t>(best)] - target);
    if (d < best_d || (latest && d == best_d)) best = k;
  }
  return best;
}
}  // namespace

double add_occluder(std::span<float> scene, std::span<const float> object, int width, int height, double fraction,
                    double t) {
  if (fraction <= 0) return 0.0;
  const Footprint f = footprint(object, width, height);
  if (f.pixels == 0) return 0.0;
  // The band covers cumulative share [s (1 - fraction), s (1 - fraction) + fraction]; s sweeps 0..1.
  const double s = 0.5 + 0.5 * std::sin(2.0 * std::numbers::pi * t / kOccluderSweepPeriod);
  const double start = s * (1.0 - fraction);
  const int first = nearest_boundary(f.columns_before, start, 0, width - 1, true);
  // The end is placed relative to the rounded start, so the hidden share misses fraction by at most
  // half a column's worth.
  const int end = nearest_boundary(f.columns_before, f.columns_before[static_cast<size_t>(first)] + fraction, first + 1,
                                   width, false);

  const float bar = static_cast<float>(std::max(static_cast<double>(f.nearest) - kGapToObject, kNearestBar));
  const int row0 = std::max(0, f.top - kRowMargin), row1 = std::min(height - 1, f.bottom + kRowMargin);
  long hidden = 0;
  for (int v = row0; v <= row1; ++v)
    for (int u = first; u < end; ++u) {
      const size_t i = static_cast<size_t>(v) * static_cast<size_t>(width) + static_cast<size_t>(u);
      if (scene[i] > 0.0f && scene[i] <= bar) continue;  // something is already in front of the bar
      scene[i] = bar;
      if (object[i] > 0.0f) ++hidden;
    }
  return static_cast<double>(hidden) / static_cast<double>(f.pixels);
}

}  // namespace depthtrack::synth
