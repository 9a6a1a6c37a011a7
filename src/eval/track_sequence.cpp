#include <depthtrack/evaluation.hpp>

#include "core/stopwatch.hpp"
#include "eval/frame_reader.hpp"

namespace depthtrack {

std::vector<TrackedFrame> track_sequence(const Sequence& sequence, const Mesh& mesh, const TrackerConfig& config,
                                         const Pose& initial, const InitialSpread& spread,
                                         const std::function<void(size_t, const TrackedFrame&)>& on_frame) {
  FrameReader reader(sequence);  // first, so that the first frames decode while the tracker starts up
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
    const DepthImage depth = reader.next();
    const Stopwatch latency;
    out.estimate = tracker.update(depth, f.timestamp);
    out.latency_ms = latency.elapsed_ms();
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
  return frames;
}

}  // namespace depthtrack
