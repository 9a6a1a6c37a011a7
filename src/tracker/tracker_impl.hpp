#pragma once
// What a Tracker holds between frames, which its public header keeps private: the device and the filter on
// it, the supervisor (confidence, loss, search), the particle budget, the cameras and configuration, and the
// frame-to-frame state; and InternalTracker, the Tracker a MultiTracker drives through them.
#include <Eigen/Core>
#include <cstddef>
#include <depthtrack/search_candidates.hpp>
#include <depthtrack/tracker.hpp>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "core/mesh_symmetry.hpp"
#include "model/filter_backend.hpp"
#include "tracker/held_turn.hpp"
#include "tracker/particle_budget.hpp"
#include "tracker/residual_structure.hpp"
#include "tracker/track_supervisor.hpp"

namespace depthtrack {

struct Tracker::Impl {
  // The checks are the constructors' (Tracker); then the filter on device.
  Impl(std::shared_ptr<Device> device, const Camera& sensor, const Mesh& checked, const TrackerConfig& config);

  void initialize(const Pose& pose, const InitialSpread& spread);
  Estimate initialize_global(const DepthImage& depth, double timestamp, const InitHint& hint);
  void set_particle_count(int count);
  // With a budget: the next frame's particle count, set on the filter; reseed: it starts a new cloud.
  void choose_particle_count(bool reseed);
  // The poses the budget's prime scores at once: 1 on the host, a batch on a device (particle_time_ms).
  int prime_poses() const;
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
  void start_frame(const DepthImage& working, const std::function<const DepthImage&()>& sensor_frame, double timestamp);
  void enqueue_frame(const DepthImage& working, double timestamp);  // start_frame after the search
  Estimate finish_frame(const DepthImage& working);
  // finish_frame in two halves: collect_frame waits for the estimate and checks it (on the thread that
  // enqueued it: a GL renderer's timer events are read there); assess_frame, host work on this tracker's
  // own state only, may run on another thread, side by side with other trackers' assessments.
  Estimate collect_frame();
  void assess_frame(Estimate& e, const DepthImage& working);
  // assess_frame before the budget's look; returns the frame's own confidence (0 without data).
  double assess_confidence(Estimate& e, const DepthImage& working);
  // The reported covariance from the fit's, once the frame's status and evidence are known. Returns the
  // variance of the turn about the mesh's axis of symmetry before the report leaves it undetermined
  // (HeldTurn's input: +infinity when nothing is determined, NaN without an axis or a fit).
  double report_covariance(Estimate& e, const ResidualStructure& residual) const;
  // The pose reported with its turn about the axis of symmetry held (HeldTurn); a lost frame restarts it.
  void hold_turn(Estimate& e, double turn_variance);
  // The working-resolution depth of the mesh at `pose` (0 where it covers nothing): the confidence's
  // own rendering when it drew that very pose last, else drawn now by the same rasterizer.
  const std::vector<float>& silhouette(const Pose& pose);

  struct PendingFrame {
    double timestamp = 0;
    bool recovered = false;
    double search_ms = 0;
    search::SearchTimes search_times;
    size_t search_poses = 0;
  };

  std::shared_ptr<Device> device_;
  Camera sensor_;
  int decimation_ = 1;
  Camera working_;
  TrackerConfig config_;
  std::unique_ptr<FilterBackend> backend_;
  std::unique_ptr<TrackSupervisor> supervisor_;
  std::unique_ptr<ParticleBudget> budget_;  // null without config.budget_ms
  int particle_count_ = 0;                  // what the filter runs now
  bool initialized_ = false;
  bool has_previous_ = false;
  double previous_timestamp_ = 0;
  Pose last_pose_;            // the last frame's estimate: where a search after a gap looks
  bool gap_pending_ = false;  // a gap came with no valid pixel to search: the next frame that has one searches
  size_t frames_since_initialize_ = 0;
  Eigen::Vector3d centre_ = Eigen::Vector3d::Zero();  // the mesh's, where initialize() checks the start
  std::optional<SymmetryAxis> symmetry_;              // the mesh's axis of near symmetry, if it has one
  std::optional<HeldTurn> held_turn_;                 // the reported turn about that axis, filtered
  size_t mesh_triangles_ = 0, drawn_triangles_ = 0;
  unsigned search_round_ = 0;                       // varies each recovery search's perturbations
  std::vector<SearchCandidate> search_candidates_;  // the last initialize_global's; none after initialize()
  PendingFrame pending_;                            // between start_frame and finish_frame
  bool frame_pending_ = false;
};

// A Tracker whose frame halves the library reaches (MultiTracker runs every object's start before any
// finish): the same constructors, and its Impl.
class InternalTracker : public Tracker {
 public:
  using Tracker::Tracker;
  Impl& impl() { return *impl_; }
  const Impl& impl() const { return *impl_; }
};

}  // namespace depthtrack
