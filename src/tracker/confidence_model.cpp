#include "tracker/confidence_model.hpp"

#include <algorithm>
#include <cmath>

namespace depthtrack {

namespace {
// The model's inputs, each a share or a ratio that means the same for any object and resolution.
// Their coefficients come from scripts/calibrate-confidence.py (the order it prints them in).
struct Coefficients {
  double bias, visible, contradicted, visible_rms, separated_free, missing;
};
constexpr Coefficients kFitted{-0.04, 0.75, -13.88, -3.1, 6.83, 2.87};
// visible_rms is read up to this: beyond it the surface is no longer the pose's anyway.
constexpr double kRmsCap = 3.0;
}  // namespace

double pose_confidence(const PoseEvidence& e) {
  const double measured = e.visible + e.occluded + e.contradicted;
  if (e.pixels == 0 || !(measured > 0)) return 0.0;
  // The outline's share that could be judged at all (the rest lies against nearer surfaces), times
  // the share of it that sees past the edge: an outline hidden by occluders says nothing.
  const double separated_free = e.separated * (1.0 - e.outline_nearer);
  const double z = kFitted.bias + kFitted.visible * e.visible + kFitted.contradicted * e.contradicted +
                   kFitted.visible_rms * std::min(e.visible_rms, kRmsCap) + kFitted.separated_free * separated_free +
                   kFitted.missing * e.missing;
  return 1.0 / (1.0 + std::exp(-z));
}

}  // namespace depthtrack
