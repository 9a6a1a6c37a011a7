#pragma once
/// @file
/// The particle filter: one update() per depth frame.
#include <cstddef>
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
#include <memory>
#include <string>
#include <utility>

namespace depthtrack {

/// Tracks one rigid object (a mesh) through a stream of depth frames: initialize() or initialize_global(), then
/// update() once per frame, each returning that frame's Estimate. Every error is an InputError naming the
/// problem (bad mesh, camera, configuration, frame or call order) or a BackendError from the device.
class Tracker {
 public:
  /// Opens a device of its own from config.backend. sensor: the intrinsics of the images update() receives;
  /// they are decimated to the configured working resolution (config.width x config.height pixels), which
  /// must divide the sensor resolution. InputError for an invalid mesh, camera or configuration.
  Tracker(const Mesh& mesh, const Camera& sensor, const TrackerConfig& config);
  /// The same on a shared device: trackers on one Device share its compute queue and compiled programs.
  /// config.backend is replaced by the device's selector (config() reports it); InputError for a null device.
  Tracker(std::shared_ptr<Device> device, const Mesh& mesh, const Camera& sensor, const TrackerConfig& config);
  /// Releases the filter; the device goes with its last tracker.
  ~Tracker();
  Tracker(Tracker&&) noexcept;             ///< Moves the filter and its state; the moved-from tracker is empty.
  Tracker& operator=(Tracker&&) noexcept;  ///< Moves the filter and its state; the moved-from tracker is empty.

  /// Draws the particles around pose (metres, camera frame; gaussian per axis with spread's metres and
  /// radians, about the mesh's centre, local frame). The quaternion is normalized (zero is an InputError);
  /// the mesh's centre must lie at a depth in [near_plane, max_depth] metres; the spread must be finite, at
  /// most max_depth and a full turn (2 pi rad).
  void initialize(const Pose& pose, const InitialSpread& spread = {});
  /// Finds the object in this frame without a pose: scores a coarse-to-fine set of pose hypotheses
  /// (translations from the depth inside the hint's region, rotations covering SO(3)), seeds the
  /// particles around the best and runs this frame's update; returns its estimate. timestamp in seconds.
  /// InputError for an empty box, a box outside the image, or no valid depth in the region.
  Estimate initialize_global(const DepthImage& depth, double timestamp, const InitHint& hint = {});
  /// Runs one frame. depth (metres) must have the sensor's size; timestamps (seconds) must increase. Depths
  /// beyond the model's max_depth count as missing; a frame with no valid pixel is a dropout: the
  /// filter predicts only and the estimate's status is NoData. An estimate that is not finite is an
  /// InputError naming the frame; so is a call before initialize().
  /// While the status is lost (and config.recovery.enabled), the frame first runs a global search
  /// within config.recovery.budget_ms and re-seeds the filter when it finds the object.
  Estimate update(const DepthImage& depth, double timestamp);
  /// The same for a caller's buffer in place (float32 metres or uint16 units, any row stride): it is
  /// validated (DepthView::validate, the sensor's size) and read once into the working resolution; the
  /// whole image is converted only when a search runs. Same input, same estimates as a DepthImage.
  Estimate update(const DepthView& depth, double timestamp);
  /// initialize_global for a caller's buffer in place (validated as update(DepthView) does).
  Estimate initialize_global(const DepthView& depth, double timestamp, const InitHint& hint = {});

  /// The camera of the working resolution: the sensor's, decimated.
  const Camera& working_camera() const;
  /// The configuration in use (with a shared device, its backend is the device's selector).
  const TrackerConfig& config() const;
  /// One line naming the backend, its device and the atlas' renderer and hand-off path.
  std::string backend_description() const;
  /// Triangles of the mesh given, after validation dropped degenerate ones.
  size_t mesh_triangles() const;
  /// Triangles of the mesh drawn (TrackerConfig::simplify_error simplified it: every particle, the
  /// refinement and the confidence draw this one).
  size_t drawn_triangles() const;
  /// Width and height (pixels) of the occlusion state window of the last frame (TrackerConfig::occlusion_window:
  /// the automatic one's size at the start and as it grew; the image's with `full`).
  std::pair<int, int> occlusion_window_size() const;
  /// The following frames run with `count` particles, 1 to config.particles (every backend, the same draw):
  /// the cloud is resampled to that many from its weights. With
  /// config.budget_ms the tracker sets the count itself before each frame (Estimate::particles says it),
  /// and this is an InputError.
  void set_particle_count(int count);

 protected:
  /// The filter, its supervisor and the frame-to-frame state: the library's own.
  struct Impl;
  std::unique_ptr<Impl> impl_;  ///< Never null but after a move.
};

}  // namespace depthtrack
