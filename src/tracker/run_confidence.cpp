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

double RunConfidence::update(const PoseEvidence& evidence, double time_s, double lost_below) {
  const double frame = pose_confidence(evidence);
  if (!(frame >= lost_below)) {
    carried_.reset();
    return frame;
  }
  double prior = 0.0;  // logit 1/2: a run's first frame is its evidence alone
  if (carried_) {
    const double hazard = 1.0 - std::pow(1.0 - kHazard, std::max(0.0, time_s - carried_time_s_) / kFramePeriod);
    prior = logit((1.0 - hazard) * *carried_ + 0.5 * hazard);
  }
  const double z = std::clamp(prior + pose_support(evidence) * logit(evidence_probability(evidence)), -40.0, 40.0);
  carried_ = 1.0 / (1.0 + std::exp(-z));
  carried_time_s_ = time_s;
  return std::max(frame, std::min(*carried_, kMostConfident));
}

}  // namespace depthtrack
