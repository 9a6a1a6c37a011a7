#include "tracker/run_confidence.hpp"

#include <algorithm>
#include <cmath>

#include "tracker/confidence_model.hpp"

namespace depthtrack {

namespace {
double logit(double p) {
  p = std::clamp(p, 1e-9, 1.0 - 1e-9);
  return std::log(p / (1.0 - p));
}
}  // namespace

RunConfidence::Reading RunConfidence::update(const PoseEvidence& evidence, double time_s, double lost_below) {
  const double support = pose_support(evidence), odds = evidence_log_odds(evidence);
  const double frame = support * logistic(odds);  // pose_confidence, to the bit
  if (!(frame >= lost_below)) {
    carried_.reset();
    return {frame, frame};
  }
  double prior = 0.0;  // logit 1/2: a run's first frame is its evidence alone
  if (carried_) {
    const double hazard = 1.0 - std::pow(1.0 - kHazard, std::max(0.0, time_s - carried_time_s_) / kFramePeriod);
    prior = logit((1.0 - hazard) * *carried_ + 0.5 * hazard);
  }
  const double z = std::clamp(prior + support * odds, -40.0, 40.0);
  carried_ = logistic(z);
  carried_time_s_ = time_s;
  return {frame, std::max(frame, std::min(*carried_, kMostConfident))};
}

}  // namespace depthtrack
