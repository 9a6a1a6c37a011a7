#pragma once
// Several objects in one depth stream: a Tracker per object, all on one Device (each program compiled
// once, each tracker on a compute queue of its own). A frame is checked and decimated once, every object's
// update is enqueued, then every estimate collected, so the device runs the objects side by side, and the
// estimates' confidences are assessed side by side on the host. With
// mutual occlusion, the working-resolution pixels the other objects' previous estimates hide are missing
// for each object, so one object's surface neither rewards nor punishes another's likelihood.
#include <depthtrack/device.hpp>
#include <depthtrack/tracker.hpp>
#include <functional>
#include <memory>
#include <vector>

namespace depthtrack {

class MutualOcclusion;
class ThreadPool;

// Host wall time of each stage of the last MultiTracker::update, ms: where a several-object frame's time
// goes. The stages follow one another on the calling thread; meanwhile the pool collects and assesses the
// objects already enqueued (except with the GL renderer). Each object's own steps are in its
// Estimate::timings.
struct MultiStageTimings {
  double working_ms = 0;    // the frame checked and decimated to the working resolution, once
  double occluders_ms = 0;  // mutual occlusion: the objects' previous estimates drawn (the last frame drew them)
  double masks_ms = 0;      // mutual occlusion: each object's masked working frame
  double enqueue_ms = 0;    // every object's start_frame: upload, enqueue (a host filter: its whole update)
  std::vector<double> object_enqueue_ms;  // each object's share of enqueue_ms, in order
  double collect_ms = 0;     // from the last enqueue to the last estimate collected (earlier ones meanwhile)
  double confidence_ms = 0;  // confidences, statuses and next layers still running after that (a pool)
  double total_ms = 0;       // the whole update
};

class MultiTracker {
 public:
  // InputError for no mesh or a null device; each tracker as Tracker(device, mesh, sensor, config).
  // host_threads: the threads the objects' host steps (collecting, confidence, occluder layers) share, the
  // caller's included; 0: one per object, at most the hardware's. Any count gives the same estimates.
  MultiTracker(std::shared_ptr<Device> device, const std::vector<Mesh>& meshes, const Camera& sensor,
               const TrackerConfig& config, bool mutual_occlusion = true, int host_threads = 0);
  ~MultiTracker();
  MultiTracker(MultiTracker&&) noexcept;
  MultiTracker& operator=(MultiTracker&&) noexcept;

  size_t size() const { return trackers_.size(); }
  // Object `object`'s start (Tracker::initialize); InputError for an index out of range.
  void initialize(size_t object, const Pose& pose, const InitialSpread& spread = {});
  // One frame for every object, in the order the meshes were given; every object must be initialized.
  std::vector<Estimate> update(const DepthImage& depth, double timestamp);
  std::vector<Estimate> update(const DepthView& depth, double timestamp);

  const Tracker& tracker(size_t object) const;
  const Device& device() const { return *device_; }
  const MultiStageTimings& last_timings() const { return timings_; }

 private:
  void check_initialized() const;  // InputError naming the first object without a start
  // One frame, already at the working resolution, for every object; sensor_frame() as Tracker's.
  std::vector<Estimate> run(const DepthImage& working, const std::function<const DepthImage&()>& sensor_frame,
                            double timestamp);
  // run's two ways of starting every object (start(j)) and collecting and assessing it (assess(j) after
  // the estimate): collected on the pool as the later objects are enqueued, or on this thread (GL).
  void pipelined(size_t n, const std::function<void(size_t)>& start, const std::function<void(size_t)>& assess,
                 std::vector<Estimate>& estimates);
  void collected_here(size_t n, const std::function<void(size_t)>& start, const std::function<void(size_t)>& assess,
                      std::vector<Estimate>& estimates);

  std::shared_ptr<Device> device_;
  std::vector<Tracker> trackers_;
  // Each object's occluder layer: its tracker's silhouette at its previous estimate (the confidence drew it).
  std::vector<std::vector<float>> occluder_layers();

  std::unique_ptr<MutualOcclusion> occlusion_;  // null when off or with one object
  // The objects' host steps (collecting, confidence, occluder layers) side by side: a thread per object, at
  // most the hardware's; with the GL renderer the device's results are collected on the calling thread.
  std::unique_ptr<ThreadPool> pool_;
  bool collects_on_pool_ = true;  // false with the GL renderer: its timer events are read on this thread
  MultiStageTimings timings_;
  std::vector<Pose> poses_;  // each object's previous estimate (or start)
  std::vector<bool> initialized_;
};

}  // namespace depthtrack
