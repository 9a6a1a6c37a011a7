#pragma once
/// @file
/// A frame's estimate: the pose the tracker reports, with its velocity, covariance, confidence, status and the
/// frame's step timings.
#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <depthtrack/pose.hpp>
#include <depthtrack/pose_evidence.hpp>

namespace depthtrack {

/// Each step's time in the last update, ms. Reference: host clock. Compute backends enqueue the frame without waiting
/// and read device times from its events after it: propagate, weigh, resample (summarize and the resampling kernels,
/// run every frame, the refinement's cloud shift with them), refine (the fit; with the one-launch layout below 16,384
/// particles it summarizes in its own launch, so the summary's time is refine's there; where weigh draws the atlas
/// for up to 4,096 particles it moves them too, propagate then 0), render with renderer kernel, and with gl where GL
/// has timer queries (GL_TIME_ELAPSED; render_on_device says which). Host wall time: render with cpu, or gl without
/// timer queries (around a glFinish), handoff (as far as the host waits for it; with gl and timer queries it includes
/// the wait for GL to finish the draw; 0 with kernel and on the reference), total_ms and search_ms.
struct StepTimings {
  double propagate_ms = 0, render_ms = 0, handoff_ms = 0, weigh_ms = 0, resample_ms = 0, total_ms = 0;
  /// render_ms is the device's (compute event or GL timer query) rather than the host clock's.
  bool render_on_device = false;
  double refine_ms = 0;
  /// Global search (initialize_global, or recovery while lost), wall-clock; included in total_ms.
  double search_ms = 0;
  /// Of search_ms: scoring the search's poses on the backend; each pose's agreement with the caller's box
  /// (host); fitting the best candidates to the likelihood's optimum (host, their scoring excepted).
  double search_scoring_ms = 0, search_box_ms = 0, search_fit_ms = 0;
  /// The estimate's confidence and status: its silhouette drawn and compared on the host, wall-clock;
  /// included in total_ms.
  double confidence_ms = 0;
  /// Compute backends: the frame's depth handed to the device (staged and enqueued), host wall time; included
  /// in total_ms. 0 on the host.
  double upload_ms = 0;
  /// Compute backends, host wall time: handing the frame's device work over (the upload included), and
  /// then waiting for its estimate. What total_ms holds beyond these and confidence_ms is the host's
  /// reading of the results. 0 on the host.
  double enqueue_ms = 0, wait_ms = 0;
};

/// What a frame's estimate rests on. Tracking: the confidence is at least loss.lost_below, so the pose can
/// be acted on. Lost: it is not (the object is hidden, gone or the estimate is wrong); while it
/// stays so for loss.search_after frames, or after a gap in time the motion model cannot bridge, the
/// tracker searches for the object. NoData: the frame had no valid pixel (a sensor dropout), so the
/// filter only predicted: the pose is the motion model's guess.
enum class TrackStatus { Tracking, Lost, NoData };
/// "tracking", "lost" or "no-data".
const char* to_string(TrackStatus status);

/// What the tracker says about one frame: the pose, its uncertainty and confidence, and how it was computed.
struct Estimate {
  /// camera_from_object: the refined pose, or the weighted mean when refinement is off. For a mesh with an axis of
  /// near symmetry (can, bowl, mug) its turn about that axis is filtered over the frames (held where the depth
  /// cannot tell it, following it where the part that breaks the symmetry is seen), so the frame does not spin.
  Pose pose;
  Eigen::Vector3d linear_velocity = Eigen::Vector3d::Zero();   ///< m/s, object's local frame
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();  ///< rad/s, object's local frame
  double effective_sample_size = 0;                            ///< 1 / sum w^2 before resampling
  double max_log_likelihood = 0;                               ///< best particle's log L of this frame
  double mean_log_likelihood = 0;                              ///< weighted mean of log L
  bool resampled = false;
  /// Covariance of the refined pose's error, as a twist in the camera frame about the mesh's centre:
  /// rows/columns 0-2 the centre's position (m), 3-5 the rotation vector (rad). The fit's normal
  /// equations (inverse Gauss-Newton Hessian of the log-likelihood) scaled by the depth residual at the
  /// pose (docs/covariance.md: coverage per sequence). +infinity on the diagonal, 0 across: an axis the depth cannot
  /// determine (a face seen face-on), the others holding with it fixed; every axis when lost or under a quarter of the
  /// silhouette's depth agrees with the pose. A turn about the mesh's axis of near symmetry (can, bowl, mug) has a
  /// variance of 100 along it: leave out the finite block's directions of variance 1 or more. NaN when refinement is
  /// off or the fit had too few pixels. The principal point's half pixel is in the centre's x and y variances.
  Eigen::Matrix<double, 6, 6> covariance = Eigen::Matrix<double, 6, 6>::Constant(std::nan(""));
  StepTimings timings;
  int refine_iterations = 0;  ///< steps the refinement tried (each one rendering of the pose); 0 when off
  /// The probability that the pose lies within tolerance of the truth (ADD-S at most 10 mm and a tenth
  /// of the object's diameter): this frame's `evidence` by a calibrated model and, where that supports
  /// the pose (at least loss.lost_below), the run of supported frames before it, at most 0.99
  /// (docs/confidence.md); 0 for a frame without data or a silhouette that covers no measured pixel.
  double confidence = 0;
  PoseEvidence evidence;  ///< what the frame's depth says about the pose, at the working resolution
  TrackStatus status = TrackStatus::Tracking;
  bool recovered = false;   ///< this frame re-seeded the filter: a search while lost found it, or after a gap in time
  size_t search_poses = 0;  ///< poses this frame's global search scored (0: none ran)
  int particles = 0;        ///< particles this frame's update ran with
};

}  // namespace depthtrack
