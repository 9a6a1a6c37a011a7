#pragma once
// A tracked frame's errors against its ground truth, shared by the one- and several-object loops.
#include <depthtrack/evaluation.hpp>
#include <optional>

namespace depthtrack {

// Sets frame's ground truth and, when there is one, its translation, rotation and ADD-S errors; adds is
// built from mesh on first use.
inline void score_frame(TrackedFrame& frame, const std::optional<Pose>& truth, const Mesh& mesh,
                        std::optional<AddsMetric>& adds) {
  frame.ground_truth = truth;
  if (!truth) return;
  frame.translation_error = translation_error(frame.estimate.pose, *truth);
  frame.rotation_error = rotation_error(frame.estimate.pose, *truth);
  if (!adds) adds.emplace(mesh);
  frame.adds = (*adds)(frame.estimate.pose, *truth);
}

}  // namespace depthtrack
