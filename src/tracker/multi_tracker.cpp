#include <algorithm>
#include <depthtrack/error.hpp>
#include <depthtrack/multi_tracker.hpp>
#include <exception>
#include <functional>
#include <optional>

#include "core/stopwatch.hpp"
#include "core/thread_pool.hpp"
#include "tracker/mutual_occlusion.hpp"
#include "tracker/tracker_impl.hpp"

namespace depthtrack {

struct MultiTracker::Impl {
  std::vector<Estimate> update(const DepthImage& depth, double timestamp);
  std::vector<Estimate> update(const DepthView& depth, double timestamp);
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
  // Each object's occluder layer: its tracker's silhouette at its previous estimate (the confidence drew it).
  std::vector<std::vector<float>> occluder_layers();

  std::shared_ptr<Device> device_;
  std::vector<InternalTracker> trackers_;
  std::unique_ptr<MutualOcclusion> occlusion_;  // null when off or with one object
  // The objects' host steps (collecting, confidence, occluder layers) side by side: a thread per object, at
  // most the hardware's; with the GL renderer the device's results are collected on the calling thread.
  std::unique_ptr<ThreadPool> pool_;
  bool collects_on_pool_ = true;  // false with the GL renderer: its timer events are read on this thread
  MultiStageTimings timings_;
  std::vector<Pose> poses_;  // each object's previous estimate (or start)
  std::vector<bool> initialized_;
};

MultiTracker::MultiTracker(std::shared_ptr<Device> device, const std::vector<Mesh>& meshes, const Camera& sensor,
                           const TrackerConfig& config, bool mutual_occlusion, int host_threads)
    : impl_(std::make_unique<Impl>()) {
  auto& device_ = impl_->device_;
  auto& trackers_ = impl_->trackers_;
  device_ = std::move(device);
  if (!device_) throw InputError("several-object tracker: the device is null (open one with Device::open)");
  if (meshes.empty()) throw InputError("several-object tracker: no mesh given");
  if (host_threads < 0 || host_threads > 1024)
    throw InputError("several-object tracker: host_threads is " + std::to_string(host_threads) +
                     ": give 0 (one per object) or a count from 1 to 1024");
  for (const Mesh& mesh : meshes) trackers_.emplace_back(device_, mesh, sensor, config);
  impl_->poses_.resize(meshes.size());
  impl_->initialized_.assign(meshes.size(), false);
  const Camera& working = trackers_.front().working_camera();
  if (mutual_occlusion && meshes.size() > 1) impl_->occlusion_ = std::make_unique<MutualOcclusion>(meshes, working);
  const int objects = static_cast<int>(std::min<size_t>(meshes.size(), 1024));
  impl_->pool_ = std::make_unique<ThreadPool>(host_threads > 0 ? host_threads : std::min(objects, hardware_threads()));
  impl_->collects_on_pool_ = config.renderer != Renderer::Gl;
}

MultiTracker::~MultiTracker() = default;
MultiTracker::MultiTracker(MultiTracker&&) noexcept = default;
MultiTracker& MultiTracker::operator=(MultiTracker&&) noexcept = default;

size_t MultiTracker::size() const {
  return impl_->trackers_.size();
}

const Device& MultiTracker::device() const {
  return *impl_->device_;
}

const MultiStageTimings& MultiTracker::last_timings() const {
  return impl_->timings_;
}

const Tracker& MultiTracker::tracker(size_t object) const {
  if (object >= impl_->trackers_.size())
    throw InputError("object " + std::to_string(object) + " does not exist: there are " +
                     std::to_string(impl_->trackers_.size()));
  return impl_->trackers_[object];
}

void MultiTracker::initialize(size_t object, const Pose& pose, const InitialSpread& spread) {
  tracker(object);  // checks the index
  impl_->trackers_[object].initialize(pose, spread);
  impl_->poses_[object] = pose;
  impl_->initialized_[object] = true;
}

std::vector<Estimate> MultiTracker::update(const DepthImage& depth, double timestamp) {
  return impl_->update(depth, timestamp);
}

std::vector<Estimate> MultiTracker::update(const DepthView& depth, double timestamp) {
  return impl_->update(depth, timestamp);
}

void MultiTracker::Impl::check_initialized() const {
  for (size_t j = 0; j < trackers_.size(); ++j)
    if (!initialized_[j]) throw InputError("object " + std::to_string(j) + " was not initialized");
}

std::vector<Estimate> MultiTracker::Impl::update(const DepthImage& depth, double timestamp) {
  check_initialized();
  const Stopwatch clock;
  timings_ = MultiStageTimings{};
  DepthImage storage;
  // Every tracker has the sensor's camera and the working one: the frame is checked and decimated once.
  const DepthImage& working = trackers_.front().impl().working_frame(depth, storage);
  timings_.working_ms = clock.elapsed_ms();
  std::vector<Estimate> estimates = run(
      working, [&depth]() -> const DepthImage& { return depth; }, timestamp);
  timings_.total_ms = clock.elapsed_ms();
  return estimates;
}

std::vector<Estimate> MultiTracker::Impl::update(const DepthView& depth, double timestamp) {
  check_initialized();
  const Stopwatch clock;
  timings_ = MultiStageTimings{};
  const DepthImage working = trackers_.front().impl().working_frame(depth);
  timings_.working_ms = clock.elapsed_ms();
  std::optional<DepthImage> sensor;  // converted whole only if a lost object's search needs it
  std::vector<Estimate> estimates = run(
      working,
      [&]() -> const DepthImage& {
        if (!sensor) sensor = depth.to_image();
        return *sensor;
      },
      timestamp);
  timings_.total_ms = clock.elapsed_ms();
  return estimates;
}

// The previous frame drew each object at its estimate, which is poses_[k], once it was collected (run,
// or the host confidence): that rendering is the layer, so only a start (or a failed frame) draws here.
std::vector<std::vector<float>> MultiTracker::Impl::occluder_layers() {
  std::vector<std::vector<float>> layers(trackers_.size());
  pool_->run(trackers_.size(), [&](size_t k, int) { layers[k] = trackers_[k].impl().silhouette(poses_[k]); });
  return layers;
}

// Every object's frame is enqueued (each tracker has a compute queue of its own): the device runs the
// objects' work side by side. With mutual occlusion each object's working frame hides what the others'
// previous estimates cover, so none waits for another's estimate.
std::vector<Estimate> MultiTracker::Impl::run(const DepthImage& working,
                                              const std::function<const DepthImage&()>& sensor_frame,
                                              double timestamp) {
  const size_t n = trackers_.size();
  std::vector<DepthImage> masked(occlusion_ ? n : 0);
  const auto frame_of = [&](size_t j) -> const DepthImage& { return occlusion_ ? masked[j] : working; };
  std::vector<Estimate> estimates(n);
  if (occlusion_) {
    Stopwatch clock;
    // Every mask is made before any object starts: a lost object's search redraws its silhouette.
    const std::vector<std::vector<float>> layers = occluder_layers();
    timings_.occluders_ms = clock.lap_ms();
    for (size_t j = 0; j < n; ++j) masked[j] = occlusion_->frame_for(j, working, poses_, layers);
    timings_.masks_ms = clock.lap_ms();
  }
  const auto start = [&](size_t j) {
    const Stopwatch own;
    trackers_[j].impl().start_frame(frame_of(j), sensor_frame, timestamp);
    timings_.object_enqueue_ms.push_back(own.elapsed_ms());
    timings_.enqueue_ms += timings_.object_enqueue_ms.back();
  };
  // After its estimate: the confidence and status, then the next frame's occluder layer (this estimate
  // drawn: the host confidence drew it already; a refining backend's confidence comes from the device,
  // and nothing had drawn it), each tracker's own state only, so on any thread.
  const auto assess = [&](size_t j) {
    trackers_[j].impl().assess_frame(estimates[j], frame_of(j));
    if (occlusion_) trackers_[j].impl().silhouette(estimates[j].pose);
  };
  // Each rethrows the first failure once every started object is collected; the poses then stay.
  if (collects_on_pool_)
    pipelined(n, start, assess, estimates);
  else
    collected_here(n, start, assess, estimates);
  for (size_t j = 0; j < n; ++j) poses_[j] = estimates[j].pose;
  return estimates;
}

// Each object's estimate is waited for, assessed and its next layer drawn on the pool while this thread
// enqueues the objects after it (the device finishes the first objects during the later enqueues: on
// NVIDIA OpenCL an object's enqueue is most of its frame). collect_ms runs from the last enqueue to the
// last collection, confidence_ms from there to the last assessment. A failed start drops the objects
// after it; every started one is still collected (ThreadPool::run_as_released), so none is left mid-frame.
void MultiTracker::Impl::pipelined(size_t n, const std::function<void(size_t)>& start,
                                   const std::function<void(size_t)>& assess, std::vector<Estimate>& estimates) {
  const Stopwatch clock;
  double enqueued_at = 0;
  std::vector<double> collected_at(n, 0.0);
  std::exception_ptr failure;
  try {
    pool_->run_as_released(
        n,
        [&](const std::function<void()>& release) {
          for (size_t j = 0; j < n; ++j) {
            start(j);
            // Before the last release, so that the last collection cannot precede it.
            if (j + 1 == n) enqueued_at = clock.elapsed_ms();
            release();
          }
        },
        [&](size_t j, int) {
          estimates[j] = trackers_[j].impl().collect_frame();
          collected_at[j] = clock.elapsed_ms();
          assess(j);
        });
  } catch (...) {
    failure = std::current_exception();
  }
  const double last_collected = *std::max_element(collected_at.begin(), collected_at.end());
  timings_.collect_ms = std::max(0.0, last_collected - enqueued_at);
  timings_.confidence_ms = std::max(0.0, clock.elapsed_ms() - std::max(enqueued_at, last_collected));
  if (failure) std::rethrow_exception(failure);
}

// With the GL renderer the estimates are collected on this thread (its timer events are read on the
// thread whose context it is), after every object is enqueued; each estimate's assessment runs on the
// pool while the next is collected. collect_ms ends with the last collection, confidence_ms is what the
// assessments take after it.
void MultiTracker::Impl::collected_here(size_t n, const std::function<void(size_t)>& start,
                                        const std::function<void(size_t)>& assess, std::vector<Estimate>& estimates) {
  std::exception_ptr failure;
  size_t started = 0;
  try {
    for (; started < n; ++started) start(started);
  } catch (...) {
    failure = std::current_exception();
  }
  // Every started frame is collected, even after a failure, so that no tracker is left mid-frame.
  Stopwatch clock;
  std::vector<size_t> collected(started);  // sized once: the pool reads entries as they are released
  try {
    pool_->run_as_released(
        started,
        [&](const std::function<void()>& release) {
          size_t count = 0;
          for (size_t j = 0; j < started; ++j) {
            try {
              estimates[j] = trackers_[j].impl().collect_frame();
              collected[count++] = j;
              release();
            } catch (...) {
              if (!failure) failure = std::current_exception();
            }
          }
          timings_.collect_ms = clock.lap_ms();
        },
        [&](size_t i, int) { assess(collected[i]); });
  } catch (...) {
    if (!failure) failure = std::current_exception();
  }
  timings_.confidence_ms = clock.lap_ms();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace depthtrack
