#include <algorithm>
#include <depthtrack/error.hpp>
#include <depthtrack/evaluation.hpp>

namespace depthtrack {

std::vector<TrackedFrame> track_sequence(const Sequence& sequence, const Mesh& mesh, const TrackerConfig& config,
                                         const Pose& initial, const InitialSpread& spread,
                                         const std::function<void(size_t, const TrackedFrame&)>& on_frame) {
  Tracker tracker(mesh, sequence.camera, config);
  tracker.initialize(initial, spread);
  std::vector<TrackedFrame> frames;
  frames.reserve(sequence.frames.size());
  std::optional<AddsMetric> adds;  // built only when some frame has ground truth to score against
  for (size_t i = 0; i < sequence.frames.size(); ++i) {
    const SequenceFrame& f = sequence.frames[i];
    TrackedFrame out;
    out.name = f.name;
    out.timestamp = f.timestamp;
    out.estimate = tracker.update(sequence.load_depth(i), f.timestamp);
    out.ground_truth = f.ground_truth;
    if (f.ground_truth) {
      out.translation_error = translation_error(out.estimate.pose, *f.ground_truth);
      out.rotation_error = rotation_error(out.estimate.pose, *f.ground_truth);
      if (!adds) adds.emplace(mesh);
      out.adds = (*adds)(out.estimate.pose, *f.ground_truth);
    }
    frames.push_back(out);
    if (on_frame) on_frame(i, frames.back());
  }
  // Dropouts are tracked through, but a sequence that never shows a valid pixel holds no data at all.
  if (!frames.empty() && std::all_of(frames.begin(), frames.end(),
                                     [](const TrackedFrame& f) { return f.estimate.status == TrackStatus::NoData; }))
    throw InputError("no frame of the sequence has a valid depth pixel (within max_depth " +
                     std::to_string(config.observation.max_depth) + " m) at the working resolution");
  return frames;
}

}  // namespace depthtrack
