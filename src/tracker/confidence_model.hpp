#pragma once
// The tracker's confidence: the probability that a pose lies within tolerance of the truth (ADD-S at
// most 10 mm and a tenth of the object's diameter), given the evidence of its silhouette. A logistic
// model whose coefficients were fitted on poses right and wrong from real and synthetic clips
// (scripts/calibrate-confidence.py; docs/confidence.md says how and how well it holds).
#include <depthtrack/pose_evidence.hpp>

namespace depthtrack {

// In [0, 1]; 0 for a silhouette with no measured pixel (nothing supports the pose), and below 0.5 for one
// with fewer than kPlanePixels seen (on the surface): the model's probability times seen / kPlanePixels.
double pose_confidence(const PoseEvidence& evidence);
// The model's relief input: how far plane_rms exceeds visible_rms (both read up to 3), 0 where a plane
// explains the seen pixels as well as the pose does. A wall or a table seen through a wrong pose leaves
// the plane's residual at the noise.
double surface_relief(const PoseEvidence& evidence);

}  // namespace depthtrack
