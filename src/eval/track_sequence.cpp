#include <algorithm>
#include <depthtrack/error.hpp>
#include <depthtrack/evaluation.hpp>
#include <depthtrack/frame_source.hpp>
#include <depthtrack/search_candidates.hpp>

#include "core/stopwatch.hpp"
#include "eval/score_frame.hpp"

namespace depthtrack {

namespace {
// The loop both starts share; first(tracker, depth, timestamp) runs frame 0. Frames come only through
// the source.
template <typename First>
std::vector<TrackedFrame> track_frames(FrameSource& source, const Mesh& mesh, Tracker& tracker, const First& first,
                                       const std::function<void(size_t, const TrackedFrame&)>& on_frame) {
  std::vector<TrackedFrame> frames;
  frames.reserve(source.size().value_or(0));
  std::optional<AddsMetric> adds;  // built only when some frame has ground truth to score against
  for (size_t i = 0;; ++i) {
    std::optional<Frame> f = source.next();
    if (!f) break;
    if (f->depth.width() != source.camera().width || f->depth.height() != source.camera().height)
      throw InputError("frame " + f->name + " is " + std::to_string(f->depth.width()) + "x" +
                       std::to_string(f->depth.height()) + ", not the source camera's " +
                       std::to_string(source.camera().width) + "x" + std::to_string(source.camera().height));
    TrackedFrame out;
    out.name = f->name;
    out.timestamp = f->timestamp;
    const Stopwatch latency;
    out.estimate = i == 0 ? first(tracker, f->depth, f->timestamp) : tracker.update(f->depth, f->timestamp);
    out.latency_ms = latency.elapsed_ms();
    score_frame(out, f->ground_truth, mesh, adds);
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

std::vector<TrackedFrame> track_source(FrameSource& source, const Mesh& mesh, const TrackerConfig& config,
                                       const Pose& initial, const InitialSpread& spread,
                                       const std::function<void(size_t, const TrackedFrame&)>& on_frame) {
  Tracker tracker(mesh, source.camera(), config);
  tracker.initialize(initial, spread);
  return track_frames(
      source, mesh, tracker, [](Tracker& t, const DepthImage& d, double ts) { return t.update(d, ts); }, on_frame);
}

std::vector<TrackedFrame> track_source_global(FrameSource& source, const Mesh& mesh, const TrackerConfig& config,
                                              const InitHint& hint,
                                              const std::function<void(size_t, const TrackedFrame&)>& on_frame) {
  Tracker tracker(mesh, source.camera(), config);
  return track_frames(
      source, mesh, tracker,
      [&hint](Tracker& t, const DepthImage& d, double ts) { return t.initialize_global(d, ts, hint); }, on_frame);
}

std::vector<TrackedFrame> track_source_global(FrameSource& source, const Mesh& mesh, const TrackerConfig& config,
                                              const InitHint& hint, std::vector<SearchCandidate>& candidates,
                                              const std::function<void(size_t, const TrackedFrame&)>& on_frame) {
  Tracker tracker(mesh, source.camera(), config);
  return track_frames(
      source, mesh, tracker,
      [&hint, &candidates](Tracker& t, const DepthImage& d, double ts) {
        Estimate e = t.initialize_global(d, ts, hint);
        candidates = search_candidates(t);
        return e;
      },
      on_frame);
}

std::vector<TrackedFrame> track_sequence(const Sequence& sequence, const Mesh& mesh, const TrackerConfig& config,
                                         const Pose& initial, const InitialSpread& spread,
                                         const std::function<void(size_t, const TrackedFrame&)>& on_frame) {
  // The source first, so that the first frames decode while the tracker starts up.
  const auto source = sequence_source(sequence);
  return track_source(*source, mesh, config, initial, spread, on_frame);
}

std::vector<TrackedFrame> track_sequence_global(const Sequence& sequence, const Mesh& mesh, const TrackerConfig& config,
                                                const InitHint& hint,
                                                const std::function<void(size_t, const TrackedFrame&)>& on_frame) {
  const auto source = sequence_source(sequence);
  return track_source_global(*source, mesh, config, hint, on_frame);
}

}  // namespace depthtrack
