#pragma once
// The particle filter: one update() per depth frame.
#include <cmath>
#include <depthtrack/camera.hpp>
#include <depthtrack/depth_image.hpp>
#include <depthtrack/depth_view.hpp>
#include <depthtrack/device.hpp>
#include <depthtrack/estimate.hpp>
#include <depthtrack/init_hint.hpp>
#include <depthtrack/initial_spread.hpp>
#include <depthtrack/mesh.hpp>
#include <depthtrack/pose.hpp>
#include <depthtrack/tracker_config.hpp>
#include <functional>
#include <memory>
#include <numbers>
#include <utility>

namespace depthtrack {

class FilterBackend;    // the per-backend implementation (reference, compute layer)
class TrackSupervisor;  // confidence, loss and global search (backend-independent)
class ParticleBudget;   // each frame's particle count under TrackerConfig::budget_ms

class Tracker {
 public:
  // sensor: the intrinsics of the images update() receives; they are decimated to the
  // configured working resolution, which must divide the sensor resolution.
  // The device is opened from config.backend (a device of its own).
  Tracker(const Mesh& mesh, const Camera& sensor, const TrackerConfig& config);
  // On a shared device: trackers on one Device share its compute queue and compiled programs.
  // config.backend is replaced by the device's selector (config() reports it).
  Tracker(std::shared_ptr<Device> device, const Mesh& mesh, const Camera& sensor, const TrackerConfig& config);
  ~Tracker();
  Tracker(Tracker&&) noexcept;
  Tracker& operator=(Tracker&&) noexcept;

  // Draws the particles around pose (gaussian, per-axis, about the mesh's centre, local frame).
  // The quaternion is normalized (zero is an InputError); the mesh's centre must lie at a depth in
  // [near_plane, max_depth]; the spread must be finite, at most max_depth and a full turn.
  void initialize(const Pose& pose, const InitialSpread& spread = {});
  // Finds the object in this frame without a pose: scores a coarse-to-fine set of pose hypotheses
  // (translations from the depth inside the hint's region, rotations covering SO(3)), seeds the
  // particles around the best and runs this frame's update; returns its estimate. InputError for
  // an empty box, a box outside the image, or no valid depth in the region.
  Estimate initialize_global(const DepthImage& depth, double timestamp, const InitHint& hint = {});
  // Runs one frame. depth must have the sensor's size; timestamps (seconds) must increase. Depths
  // beyond the model's max_depth count as missing; a frame with no valid pixel is a dropout: the
  // filter predicts only and the estimate's status is NoData. An estimate that is not finite is an
  // InputError naming the frame.
  // While the status is lost (and config.recovery.enabled), the frame first runs a global search
  // within config.recovery.budget_ms and re-seeds the filter when it finds the object.
  Estimate update(const DepthImage& depth, double timestamp);
  // The same for a caller's buffer in place (float32 metres or uint16 units, any row stride): it is
  // validated (DepthView::validate, the sensor's size) and read once into the working resolution; the
  // whole image is converted only when a search runs. Same input, same estimates as a DepthImage.
  Estimate update(const DepthView& depth, double timestamp);
  Estimate initialize_global(const DepthView& depth, double timestamp, const InitHint& hint = {});

  const Camera& working_camera() const;
  const TrackerConfig& config() const;
  std::string backend_description() const;
  // Triangles of the mesh given (after validation dropped degenerate ones) and of the mesh drawn
  // (TrackerConfig::simplify_error simplified it: every particle, the refinement and the confidence
  // draw this one).
  size_t mesh_triangles() const { return mesh_triangles_; }
  size_t drawn_triangles() const { return drawn_triangles_; }
  // Width and height of the occlusion state window of the last frame (TrackerConfig::occlusion_window:
  // the automatic one's size at the start and as it grew; the image's with `full`).
  std::pair<int, int> occlusion_window_size() const;
  // The following frames run with `count` particles, 1 to config.particles (host backends, reference and
  // cpu; the others throw InputError): the cloud is resampled to that many from its weights. With
  // config.budget_ms the tracker sets the count itself before each frame (Estimate::particles says it),
  // and this is an InputError.
  void set_particle_count(int count);

 private:
  // With a budget: the next frame's particle count, set on the filter; reseed: it starts a new cloud.
  void choose_particle_count(bool reseed);
  // The working-resolution frame (decimated only when needed); InputError for a wrong size.
  const DepthImage& working_frame(const DepthImage& depth, DepthImage& storage) const;
  // The working-resolution frame of a view, read in one pass; InputError for a wrong size.
  DepthImage working_frame(const DepthView& depth) const;
  // update() after the frame is at the working resolution; sensor_frame() gives the frame at the
  // sensor's resolution, asked for only when a search runs.
  Estimate track_frame(const DepthImage& working, const std::function<const DepthImage&()>& sensor_frame,
                       double timestamp);
  Estimate run_frame(const DepthImage& working, double timestamp);

  // track_frame in two halves, so that a MultiTracker enqueues every object's frame before it waits for
  // any: start_frame checks the timestamp, runs a lost track's search and enqueues the filter's update;
  // finish_frame collects its estimate, checks it and assesses its confidence on `working`, the frame
  // start_frame was given (which must live until then).
  friend class MultiTracker;
  void start_frame(const DepthImage& working, const std::function<const DepthImage&()>& sensor_frame, double timestamp);
  void enqueue_frame(const DepthImage& working, double timestamp);  // start_frame after the search
  Estimate finish_frame(const DepthImage& working);
  // finish_frame in two halves: collect_frame waits for the estimate and checks it (on the thread that
  // enqueued it: a GL renderer's timer events are read there); assess_frame, host work on this tracker's
  // own state only, may run on another thread, side by side with other trackers' assessments.
  Estimate collect_frame();
  void assess_frame(Estimate& e, const DepthImage& working);
  void assess_confidence(Estimate& e, const DepthImage& working);  // assess_frame before the budget's look
  // The working-resolution depth of the mesh at `pose` (0 where it covers nothing): the confidence's
  // own rendering when it drew that very pose last, else drawn now by the same rasterizer.
  const std::vector<float>& silhouette(const Pose& pose);
  struct PendingFrame {
    double timestamp = 0;
    bool recovered = false;
    double search_ms = 0;
    size_t search_poses = 0;
  };

  // Both constructors: the checks, then the filter on device.
  void construct(const Device& device, const Mesh& mesh, const TrackerConfig& config);

  std::shared_ptr<Device> device_;
  std::unique_ptr<FilterBackend> backend_;
  std::unique_ptr<TrackSupervisor> supervisor_;
  std::unique_ptr<ParticleBudget> budget_;  // null without config.budget_ms
  int particle_count_ = 0;                  // what the filter runs now
  Camera sensor_;
  Camera working_;
  TrackerConfig config_;
  int decimation_ = 1;
  bool initialized_ = false;
  bool has_previous_ = false;
  double previous_timestamp_ = 0;
  Pose last_pose_;            // the last frame's estimate: where a search after a gap looks
  bool gap_pending_ = false;  // a gap came with no valid pixel to search: the next frame that has one searches
  size_t frames_since_initialize_ = 0;
  Eigen::Vector3d centre_ = Eigen::Vector3d::Zero();  // the mesh's, where initialize() checks the start
  size_t mesh_triangles_ = 0, drawn_triangles_ = 0;
  unsigned search_round_ = 0;  // varies each recovery search's perturbations
  PendingFrame pending_;       // between start_frame and finish_frame
  bool frame_pending_ = false;
};

}  // namespace depthtrack
