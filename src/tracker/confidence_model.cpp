#include "tracker/confidence_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "tracker/silhouette_shares.hpp"

namespace depthtrack {

namespace {
// The model's inputs, each a share or a ratio that means the same for any object and resolution.
// visible + occluded + contradicted = 1, so visible is implied. Coefficients from
// scripts/calibrate-confidence.py (the order it prints them in), fitted on sampled poses and tracked
// frames of both YCB-Video clips and of synthetic handset sequences (ideal, 30 % and 90 % occluded).
// The relief lets an object seen mostly through occluders, whose outline does not stand out (a bowl
// low on a table), be trusted for the curve of what is seen of it.
struct Coefficients {
  double bias, occluded, contradicted, visible_rms, separated_free, relief;
};
constexpr Coefficients kFitted{-3.1930, 1.7135, -11.6344, -1.9042, 5.6930, 2.1661};
// visible_rms and plane_rms are read up to this: beyond it the surface is no longer the pose's anyway.
constexpr double kRmsCap = 3.0;
}  // namespace

double surface_relief(const PoseEvidence& e) {
  const double rms = std::min(e.visible_rms, kRmsCap);
  return std::max(0.0, std::min(e.plane_rms, kRmsCap) - rms);
}

double evidence_log_odds(const PoseEvidence& e) {
  const double measured = e.visible + e.occluded + e.contradicted;
  if (e.pixels == 0 || !(measured > 0)) return -std::numeric_limits<double>::infinity();
  // The outline's share that sees past the edge, of the whole outline: the part against nearer surfaces
  // (occluders) says nothing either way.
  const double separated_free = e.separated * (1.0 - e.outline_nearer);
  const double z = kFitted.bias + kFitted.occluded * e.occluded + kFitted.contradicted * e.contradicted +
                   kFitted.visible_rms * std::min(e.visible_rms, kRmsCap) + kFitted.separated_free * separated_free +
                   kFitted.relief * surface_relief(e);
  return z;
}

double logistic(double z) {
  return 1.0 / (1.0 + std::exp(-z));
}

double evidence_probability(const PoseEvidence& e) {
  return logistic(evidence_log_odds(e));
}

double pose_support(const PoseEvidence& e) {
  // A pose seen by fewer pixels than a plane needs has its evidence fitted as well by a wrong one (the
  // handset behind a 90 % occluder: 1-8 seen at 80x60, its wrong poses sliding along the visible strip):
  // the confidence counts in proportion to the pixels seen, so such a pose is never supported.
  return std::min(1.0, seen_pixels(e) / static_cast<double>(kPlanePixels));
}

double seen_pixels(const PoseEvidence& e) {
  return e.pixels * (1.0 - e.missing) * e.visible;
}

double pose_confidence(const PoseEvidence& e) {
  return pose_support(e) * evidence_probability(e);
}

}  // namespace depthtrack
