#pragma once
// What an evaluation reports of one run over a clip: how accurate the estimates were (ADD-S, its AUC) and
// how far their status and confidence can be trusted (confident but wrong, lost while right, recovery).
#include <array>
#include <depthtrack/evaluation.hpp>
#include <optional>
#include <string>
#include <vector>

namespace depthtrack {

// Wrong: ADD-S above this while the status says tracking with confidence at least kConfidentAbove.
inline constexpr double kConfidentWrongAdds = 0.020;
inline constexpr double kConfidentAbove = 0.5;
// A box start that ends, and a gap that recovers, within this ADD-S (metres).
inline constexpr double kEndsWithin = 0.010;
// A gap case has recovered when every frame from this many after the gap on is within kEndsWithin or lost.
inline constexpr size_t kRecoveryFrames = 5;

// Area under the accuracy curve: the share of values <= t, integrated over t in [0, max] and divided by
// max (YCB-Video's ADD-S AUC with max 0.1 m), which equals the mean of max(0, 1 - value / max). NaN
// values (frames without ground truth) are left out; NaN when none is left.
double adds_auc(const std::vector<double>& adds, double max = 0.1);

// The largest distance between two vertices of a mesh (metres), and how it was found.
struct MeshDiameter {
  double metres = 0;
  bool exact = true;  // over the convex hull's vertices; false: the bounding box's diagonal, an upper bound
};
// Exact from the convex hull's vertices; the bounding box's diagonal where the vertices span no volume.
MeshDiameter mesh_diameter(const Mesh& mesh);
// Within tolerance: ADD-S <= min(10 mm, 10 % of the diameter).
double adds_tolerance(double diameter);

struct CaseScores {
  size_t frames = 0, scored = 0;  // all frames, and those with ground truth (the ADD-S figures are over these)
  double mean_adds = NAN, auc = NAN, last_adds = NAN;  // metres; last: the last frame's
  size_t tracking = 0, lost = 0, no_data = 0;
  size_t confident_wrong = 0;  // ADD-S > kConfidentWrongAdds, status tracking, confidence >= kConfidentAbove
  size_t false_lost = 0;       // status lost while ADD-S <= tolerance
  // With recovery_from: whether every frame from that index on with ground truth is within kEndsWithin or
  // lost (nullopt when the clip ends before it).
  std::optional<bool> recovered;
};

bool confident_wrong(const TrackedFrame& frame);
CaseScores score_case(const std::vector<TrackedFrame>& frames, double tolerance,
                      std::optional<size_t> recovery_from = std::nullopt);

// Calibration of the confidence: frames in 10 equal bins of confidence over [0, 1] (1 in the last),
// against the share of them truly within tolerance. Frames whose confidence is not finite are left out.
struct ReliabilityBin {
  size_t frames = 0;
  double mean_confidence = NAN, share_within = NAN;  // NaN for an empty bin
};
struct Reliability {
  std::array<ReliabilityBin, 10> bins;
  size_t frames = 0;
  // Expected calibration error: sum over bins of frames / all frames * |share within - mean confidence|.
  double ece = NAN;
};
struct ConfidenceOutcome {
  double confidence = 0;
  bool within = false;
};
Reliability reliability(const std::vector<ConfidenceOutcome>& outcomes);

}  // namespace depthtrack
