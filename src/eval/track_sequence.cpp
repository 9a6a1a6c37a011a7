#include <algorithm>
#include <depthtrack/error.hpp>
#include <depthtrack/evaluation.hpp>

#include "core/stopwatch.hpp"
#include "eval/frame_reader.hpp"
#include "eval/score_frame.hpp"

namespace depthtrack {

namespace {
// The loop both starts share; first(tracker, depth, timestamp) runs frame 0. The reader decodes
// frames ahead on its own thread.
template <typename First>
std::vector<TrackedFrame> track_frames(const Sequence& sequence, const Mesh& mesh, FrameReader& reader,
                                       Tracker& tracker, const First& first,
                                       const std::function<void(size_t, const TrackedFrame&)>& on_frame) {
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
    out.estimate = i == 0 ? first(tracker, depth, f.timestamp) : tracker.update(depth, f.timestamp);
    out.latency_ms = latency.elapsed_ms();
    score_frame(out, f.ground_truth, mesh, adds);
    frames.push_back(out);
    if (on_frame) on_frame(i, frames.back());
  }
  // Dropouts are tracked through, but a sequence that never shows a valid pixel holds no data at all.
  if (!frames.empty() && std::all_of(frames.begin(), frames.end(),
                                     [](const TrackedFrame& f) { return f.estimate.status == TrackStatus::NoData; }))
    throw InputError("no frame of the sequence has a valid depth pixel (within max_depth " +
                     std::to_string(tracker.config().observation.max_depth) + " m) at the working resolution");
  return frames;
}
}  // namespace

std::vector<TrackedFrame> track_sequence(const Sequence& sequence, const Mesh& mesh, const TrackerConfig& config,
                                         const Pose& initial, const InitialSpread& spread,
                                         const std::function<void(size_t, const TrackedFrame&)>& on_frame) {
  FrameReader reader(sequence);  // first, so that the first frames decode while the tracker starts up
  Tracker tracker(mesh, sequence.camera, config);
  tracker.initialize(initial, spread);
  return track_frames(
      sequence, mesh, reader, tracker, [](Tracker& t, const DepthImage& d, double ts) { return t.update(d, ts); },
      on_frame);
}

std::vector<TrackedFrame> track_sequence_global(const Sequence& sequence, const Mesh& mesh, const TrackerConfig& config,
                                                const InitHint& hint,
                                                const std::function<void(size_t, const TrackedFrame&)>& on_frame) {
  FrameReader reader(sequence);
  Tracker tracker(mesh, sequence.camera, config);
  return track_frames(
      sequence, mesh, reader, tracker,
      [&hint](Tracker& t, const DepthImage& d, double ts) { return t.initialize_global(d, ts, hint); }, on_frame);
}

}  // namespace depthtrack
