#pragma once
/// @file
/// What a start without a pose chose among: the candidates of Tracker::initialize_global's search, each
/// with its likelihood and its confidence, so a caller can see how sure the choice was.
#include <depthtrack/evaluation.hpp>
#include <depthtrack/pose.hpp>
#include <depthtrack/tracker.hpp>
#include <functional>
#include <vector>

namespace depthtrack {

/// One pose the search kept.
struct SearchCandidate {
  Pose pose;              ///< camera_from_object, metres
  double score = 0;       ///< log-likelihood of the frame at this pose, with a fresh occlusion prior
  double confidence = 0;  ///< the confidence model at this pose, from this frame alone: the probability it lies within tolerance
};

/// The candidates of the tracker's last initialize_global, in the search's order: the best first, the
/// filter's particles drawn around the leading ones. Empty before any initialize_global.
std::vector<SearchCandidate> search_candidates(const Tracker& tracker);

/// track_source_global that also hands out the first frame's search candidates (search_candidates).
std::vector<TrackedFrame> track_source_global(FrameSource& source, const Mesh& mesh, const TrackerConfig& config,
                                              const InitHint& hint, std::vector<SearchCandidate>& candidates,
                                              const std::function<void(size_t, const TrackedFrame&)>& on_frame = {});

}  // namespace depthtrack
