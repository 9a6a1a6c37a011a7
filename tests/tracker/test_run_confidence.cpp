// A track's reported confidence: the frame's own evidence, raised by the run of supported frames before
// it, never above 0.99, never for a frame the evidence does not support. Expectations from the filter's
// formula in tracker/run_confidence.hpp, worked by hand below.
#include <catch2/catch.hpp>
#include <cmath>

#include "tracker/confidence_model.hpp"
#include "tracker/run_confidence.hpp"

using namespace depthtrack;

namespace {
constexpr double kLostBelow = 0.5;
constexpr double kFrame = 1.0 / 30;

double logit(double p) {
  return std::log(p / (1 - p));
}
double probability_of_log_odds(double z) {
  return 1 / (1 + std::exp(-z));
}

// A can's evidence as the tracker sees it on a real clip: its surface where the pose puts it, a third
// of it hidden, its residual near the noise. Supported, but not by much.
PoseEvidence can_like() {
  PoseEvidence e;
  e.pixels = 90;
  e.visible = 0.7;
  e.occluded = 0.28;
  e.contradicted = 0.02;
  e.separated = 0.8;
  e.outline_nearer = 0.2;
  e.visible_rms = 0.6;
  e.plane_rms = 1.5;
  return e;
}
}  // namespace

TEST_CASE("a run of supported frames raises the confidence, bounded by the hazard and 0.99", "[confidence]") {
  const PoseEvidence e = can_like();
  const double q = evidence_probability(e);
  REQUIRE(pose_support(e) == 1.0);  // 63 pixels seen: more than a plane needs
  REQUIRE(q == pose_confidence(e));
  REQUIRE(q > 0.5);
  REQUIRE(q < 0.9);
  RunConfidence run;
  // The first frame is its own evidence.
  CHECK(run.update(e, 0.0, kLostBelow).reported == Approx(q));
  // The second: the prior 0.9 q + 0.05 (the hazard 0.1 towards even odds), then the frame's odds.
  const double second = probability_of_log_odds(logit(0.9 * q + 0.05) + logit(q));
  CHECK(run.update(e, kFrame, kLostBelow).reported == Approx(second));
  CHECK(second > q);
  // However long the run, the prior stays under 0.95: the frame's odds times at most 19.
  double last = 0;
  for (int i = 2; i < 200; ++i) last = run.update(e, i * kFrame, kLostBelow).reported;
  CHECK(last <= probability_of_log_odds(logit(0.95) + logit(q)) + 1e-12);
  CHECK(last > second);
  // A frame of strong evidence after it: at most 0.99.
  PoseEvidence clear = e;
  clear.occluded = 0.0;
  clear.visible = 0.98;
  clear.visible_rms = 0.5;
  clear.separated = 0.95;
  clear.outline_nearer = 0.0;
  REQUIRE(pose_confidence(clear) < RunConfidence::kMostConfident);
  CHECK(run.update(clear, 200 * kFrame, kLostBelow).reported == RunConfidence::kMostConfident);
}

TEST_CASE("a frame the evidence does not support reports its own confidence and ends the run", "[confidence]") {
  const PoseEvidence e = can_like();
  const double q = pose_confidence(e);
  RunConfidence run;
  for (int i = 0; i < 10; ++i) run.update(e, i * kFrame, kLostBelow);
  PoseEvidence through = e;  // the camera sees through half of it: the pose is wrong
  through.contradicted = 0.5;
  through.visible = 0.48;
  through.occluded = 0.02;
  const double wrong = pose_confidence(through);
  REQUIRE(wrong < kLostBelow);
  const RunConfidence::Reading lost = run.update(through, 10 * kFrame, kLostBelow);
  CHECK(lost.reported == wrong);  // whatever the run before it said
  CHECK(lost.frame == wrong);
  CHECK(run.update(e, 11 * kFrame, kLostBelow).reported == Approx(q));  // a new run: its own evidence
}

TEST_CASE("a run forgets with time: a long pause, an end or few pixels seen", "[confidence]") {
  const PoseEvidence e = can_like();
  const double q = pose_confidence(e);
  RunConfidence run;
  for (int i = 0; i < 10; ++i) run.update(e, i * kFrame, kLostBelow);
  // Ten seconds later (300 frames' hazard: 1 - 0.9^300) the prior is even odds: the frame alone.
  CHECK(run.update(e, 9 * kFrame + 10.0, kLostBelow).reported == Approx(q).epsilon(1e-9));
  for (int i = 1; i < 10; ++i) run.update(e, 9 * kFrame + 10.0 + i * kFrame, kLostBelow);
  run.end_run();
  CHECK(run.update(e, 30.0, kLostBelow).reported == Approx(q));
  // Three quarters of the pixels a plane needs: the frame's odds count three quarters, on the prior.
  PoseEvidence few = e;
  few.pixels = 15;  // 15 * 0.8 = 12 seen
  few.visible = 0.8;
  few.occluded = 0.18;
  few.visible_rms = 0.5;
  REQUIRE(pose_support(few) == Approx(0.75));
  REQUIRE(pose_confidence(few) >= kLostBelow);
  const double prior = 0.9 * q + 0.05;  // after the run's only frame so far
  const double expected = probability_of_log_odds(logit(prior) + 0.75 * logit(evidence_probability(few)));
  CHECK(run.update(few, 30.0 + kFrame, kLostBelow).reported == Approx(std::max(pose_confidence(few), expected)));
}
