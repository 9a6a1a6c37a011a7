#pragma once
/// Several objects in one depth stream: a Tracker per object, all on one Device (each program compiled
/// once, each tracker on a compute queue of its own). A frame is checked and decimated once, every object's
/// update is enqueued, then every estimate collected, so the device runs the objects side by side, and the
/// estimates' confidences are assessed side by side on the host. With
/// mutual occlusion, the working-resolution pixels the other objects' previous estimates hide are missing
/// for each object, so one object's surface neither rewards nor punishes another's likelihood.
#include <depthtrack/device.hpp>
#include <depthtrack/tracker.hpp>
#include <functional>
#include <memory>
#include <vector>

namespace depthtrack {

/// Host wall time of each stage of the last MultiTracker::update, ms: where a several-object frame's time
/// goes. The stages follow one another on the calling thread; meanwhile the pool collects and assesses the
/// objects already enqueued (except with the GL renderer). Each object's own steps are in its
/// Estimate::timings.
struct MultiStageTimings {
  double working_ms = 0;    ///< the frame checked and decimated to the working resolution, once
  double occluders_ms = 0;  ///< mutual occlusion: the objects' previous estimates drawn (the last frame drew them)
  double masks_ms = 0;      ///< mutual occlusion: each object's masked working frame
  double enqueue_ms = 0;    ///< every object's start_frame: upload, enqueue (a host filter: its whole update)
  std::vector<double> object_enqueue_ms;  ///< each object's share of enqueue_ms, in order
  double collect_ms = 0;     ///< from the last enqueue to the last estimate collected (earlier ones meanwhile)
  double confidence_ms = 0;  ///< confidences, statuses and next layers still running after that (a pool)
  double total_ms = 0;       ///< the whole update
};

/// Several objects in one depth stream (see the file's notes): one Tracker per mesh on one Device.
class MultiTracker {
 public:
  /// InputError for no mesh or a null device; each tracker as Tracker(device, mesh, sensor, config).
  /// host_threads: the threads the objects' host steps (collecting, confidence, occluder layers) share, the
  /// caller's included; 0: one per object, at most the hardware's. Any count gives the same estimates.
  MultiTracker(std::shared_ptr<Device> device, const std::vector<Mesh>& meshes, const Camera& sensor,
               const TrackerConfig& config, bool mutual_occlusion = true, int host_threads = 0);
  ~MultiTracker();                                   ///< Releases every tracker and the host threads.
  MultiTracker(MultiTracker&&) noexcept;             ///< Moves every tracker; the moved-from one is empty.
  MultiTracker& operator=(MultiTracker&&) noexcept;  ///< Moves every tracker; the moved-from one is empty.

  /// The objects (meshes given).
  size_t size() const;
  /// Object `object`'s start (Tracker::initialize); InputError for an index out of range.
  void initialize(size_t object, const Pose& pose, const InitialSpread& spread = {});
  /// One frame for every object, in the order the meshes were given; every object must be initialized
  /// (InputError naming the first that is not). depth and timestamp (seconds) as Tracker::update's.
  std::vector<Estimate> update(const DepthImage& depth, double timestamp);
  /// The same for a caller's buffer in place, as Tracker::update(DepthView).
  std::vector<Estimate> update(const DepthView& depth, double timestamp);

  /// Object `object`'s tracker (its camera, configuration, backend); InputError for an index out of range.
  const Tracker& tracker(size_t object) const;
  /// The Device every object runs on.
  const Device& device() const;
  /// Each stage's time in the last update().
  const MultiStageTimings& last_timings() const;

 private:
  struct Impl;  // the trackers, the mutual occlusion and the host threads: the library's own
  std::unique_ptr<Impl> impl_;
};

}  // namespace depthtrack
