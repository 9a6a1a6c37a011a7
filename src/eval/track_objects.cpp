// Several objects through one clip: a MultiTracker on one Device, each frame decoded once.
#include <depthtrack/device.hpp>
#include <depthtrack/error.hpp>
#include <depthtrack/evaluation.hpp>
#include <depthtrack/frame_source.hpp>
#include <depthtrack/multi_tracker.hpp>
#include <optional>

#include "core/stopwatch.hpp"
#include "eval/score_frame.hpp"

namespace depthtrack {

std::vector<std::vector<TrackedFrame>> track_objects(
    const std::vector<TrackedObject>& objects, const TrackerConfig& config, const InitialSpread& spread,
    bool mutual_occlusion, const std::function<void(size_t, size_t, const TrackedFrame&)>& on_frame) {
  if (objects.empty()) throw InputError("no object to track");
  const Sequence& clip = objects.front().sequence;
  for (const TrackedObject& o : objects)
    if (o.sequence.frames.size() != clip.frames.size())
      throw InputError("object '" + o.name + "': its sequence has " + std::to_string(o.sequence.frames.size()) +
                       " frames, the first object's " + std::to_string(clip.frames.size()));
  // The source first, so that the first frames decode while the trackers start up.
  const std::unique_ptr<FrameSource> source = sequence_source(clip);
  std::vector<Mesh> meshes;
  for (const TrackedObject& o : objects) meshes.push_back(o.mesh);
  MultiTracker tracker(Device::open(config.resolved_backend()), meshes, clip.camera, config, mutual_occlusion);
  for (size_t j = 0; j < objects.size(); ++j) tracker.initialize(j, objects[j].initial, spread);

  std::vector<std::vector<TrackedFrame>> frames(objects.size());
  std::vector<std::optional<AddsMetric>> adds(objects.size());
  for (size_t i = 0; i < clip.frames.size(); ++i) {
    const std::optional<Frame> frame = source->next();
    if (!frame) throw InputError("the clip ended after " + std::to_string(i) + " frames");
    const DepthImage& depth = frame->depth;
    const Stopwatch latency;
    const std::vector<Estimate> estimates = tracker.update(depth, clip.frames[i].timestamp);
    const double latency_ms = latency.elapsed_ms();  // depth in to every object's pose out
    for (size_t j = 0; j < objects.size(); ++j) {
      const SequenceFrame& f = objects[j].sequence.frames[i];
      TrackedFrame out;
      out.name = f.name;
      out.timestamp = f.timestamp;
      out.estimate = estimates[j];
      out.latency_ms = latency_ms;
      score_frame(out, f.ground_truth, objects[j].mesh, adds[j]);
      frames[j].push_back(out);
      if (on_frame) on_frame(i, j, frames[j].back());
    }
  }
  return frames;
}

}  // namespace depthtrack
