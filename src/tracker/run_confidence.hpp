#pragma once
// The confidence a track reports: this frame's evidence (tracker/confidence_model.hpp) and the run of
// frames before it that the evidence supported. The evidence alone cannot tell a right pose from a wrong
// one whose silhouette looks the same (a can on a can of its size), so alone it reads such a pose at
// 0.7-0.85 however long the track has held it; every tracked frame the evidence supported was right
// (docs/confidence.md). A two-state forward filter over "the pose is right" carries that:
//
//     prior_t = (1 - h_t) p_{t-1} + h_t / 2          h_t = 1 - (1 - kHazard)^(elapsed / kFramePeriod)
//     logit p_t = logit prior_t + w_t logit q_t      w_t = pose_support (seen pixels / kPlanePixels, at most 1)
//
// q_t the frame's evidence_probability, read as its own odds. The hazard keeps the prior below 0.95,
// so the run multiplies a frame's odds by at most 19: it never carries a pose the frame contradicts.
// What decides the status is the frame alone: a frame below loss.lost_below is reported lost with its own
// confidence and ends the run, as does a start, a re-seeding search or a gap the motion cannot bridge. A
// supported frame reports the larger of its own confidence and the run's, at most kMostConfident.
#include <depthtrack/pose_evidence.hpp>
#include <optional>

namespace depthtrack {

class RunConfidence {
 public:
  static constexpr double kHazard = 0.1;            // per kFramePeriod: the chance the run's pose goes wrong unseen
  static constexpr double kFramePeriod = 1.0 / 30;  // s
  static constexpr double kMostConfident = 0.99;    // never more: the run is a few clips' measure

  struct Reading {
    double frame;     // the frame's own confidence (pose_confidence): what the status and the budget follow
    double reported;  // what the track reports
  };
  // evidence: this frame's, taken at time_s (seconds, increasing); lost_below: the status's threshold.
  Reading update(const PoseEvidence& evidence, double time_s, double lost_below);
  void end_run() { carried_.reset(); }  // the next frame starts a run from its own evidence

 private:
  std::optional<double> carried_;  // p of the run's last frame
  double carried_time_s_ = 0;      // and when it was taken
};

}  // namespace depthtrack
