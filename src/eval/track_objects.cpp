// Several objects through one clip: one Device, one decoded frame per step, each object in turn.
#include <depthtrack/device.hpp>
#include <depthtrack/error.hpp>
#include <depthtrack/evaluation.hpp>
#include <optional>

#include "core/stopwatch.hpp"
#include "eval/frame_reader.hpp"
#include "eval/mutual_occlusion.hpp"
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
  FrameReader reader(clip);  // first, so that the first frames decode while the trackers start up
  const auto device = Device::open(config.resolved_backend());
  std::vector<Tracker> trackers;
  std::vector<Mesh> meshes;
  std::vector<Pose> poses;
  for (const TrackedObject& o : objects) {
    trackers.emplace_back(device, o.mesh, clip.camera, config);
    trackers.back().initialize(o.initial, spread);
    meshes.push_back(o.mesh);
    poses.push_back(o.initial);
  }
  const Camera& working = trackers.front().working_camera();
  std::optional<MutualOcclusion> occlusion;
  if (mutual_occlusion && objects.size() > 1)
    occlusion.emplace(meshes, working, clip.camera.width / working.width, config.near_plane,
                      config.observation.max_depth);

  std::vector<std::vector<TrackedFrame>> frames(objects.size());
  std::vector<std::optional<AddsMetric>> adds(objects.size());
  for (size_t i = 0; i < clip.frames.size(); ++i) {
    const DepthImage depth = reader.next();
    for (size_t j = 0; j < objects.size(); ++j) {
      const SequenceFrame& f = objects[j].sequence.frames[i];
      TrackedFrame out;
      out.name = f.name;
      out.timestamp = f.timestamp;
      const Stopwatch latency;
      out.estimate = occlusion ? trackers[j].update(occlusion->frame_for(j, depth, poses), f.timestamp)
                               : trackers[j].update(depth, f.timestamp);
      out.latency_ms = latency.elapsed_ms();
      poses[j] = out.estimate.pose;
      score_frame(out, f.ground_truth, objects[j].mesh, adds[j]);
      frames[j].push_back(out);
      if (on_frame) on_frame(i, j, frames[j].back());
    }
  }
  return frames;
}

}  // namespace depthtrack
