#pragma once
// The tracker's confidence: the probability that a pose lies within tolerance of the truth (ADD-S at
// most 10 mm and a tenth of the object's diameter), given the evidence of its silhouette. A logistic
// model whose coefficients were fitted on poses right and wrong from real and synthetic clips
// (scripts/calibrate-confidence.py; docs/confidence.md says how and how well it holds).
#include <depthtrack/pose_evidence.hpp>

namespace depthtrack {

// In [0, 1]; 0 for a silhouette with no measured pixel (nothing supports the pose), and below 0.5 for one
// with fewer than kPlanePixels seen (on the surface): evidence_probability times pose_support. The
// confidence of this frame alone: a track's reported one also weighs its run (tracker/run_confidence.hpp).
double pose_confidence(const PoseEvidence& evidence);
// The probability of log odds z: 1 / (1 + e^-z).
double logistic(double z);
// The logistic model's probability alone, as if every pixel needed were seen; and its log odds (-infinity
// for a silhouette with no measured pixel).
double evidence_probability(const PoseEvidence& evidence);
double evidence_log_odds(const PoseEvidence& evidence);
// min(1, seen_pixels / kPlanePixels): how far the pixels seen can speak for the pose.
double pose_support(const PoseEvidence& evidence);
// The silhouette's pixels that see the pose's surface: measured and within the band.
double seen_pixels(const PoseEvidence& evidence);
// The model's relief input: how far plane_rms exceeds visible_rms (both read up to 3), 0 where a plane
// explains the seen pixels as well as the pose does. A wall or a table seen through a wrong pose leaves
// the plane's residual at the noise.
double surface_relief(const PoseEvidence& evidence);

}  // namespace depthtrack
