#pragma once
// Local refinement of a pose to the maximum of the per-pixel likelihood (MODEL.md) for a fixed
// occlusion map: iteratively reweighted Gauss-Newton (EM on the pixel mixture) with
// Levenberg-Marquardt damping. The pose moves by a twist (dt, dw) in the camera frame about the
// mesh's centre: the centre moves by dt, the object rotates by exp(dw) about it.
#include <Eigen/Core>
#include <depthtrack/camera.hpp>
#include <depthtrack/depth_image.hpp>
#include <depthtrack/mesh.hpp>
#include <depthtrack/pose.hpp>
#include <depthtrack/tracker_config.hpp>
#include <optional>
#include <span>
#include <vector>

#include "reference/rasterizer.hpp"

namespace depthtrack::reference {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

// Derivative of a pixel's rendered depth with respect to the twist, at the surface point (camera
// frame) with unit normal, seen along ray (its z is 1) with the centre at centre (camera frame):
// d depth / d dt = n / (n . ray), d depth / d dw = ((point - centre) x n) / (n . ray). Returns false
// for a grazing view, |cos(normal, ray)| < min_incidence, where the derivative is unreliable.
bool depth_jacobian(const Eigen::Vector3d& point, const Eigen::Vector3d& normal, const Eigen::Vector3d& ray,
                    const Eigen::Vector3d& centre, double min_incidence, Vector6d& row);

// The pose after the camera-frame twist about centre (object frame).
Pose apply_twist(const Pose& pose, const Eigen::Vector3d& centre, const Vector6d& twist);

// The twist that takes pose `from` to pose `to` (inverse of apply_twist).
Vector6d twist_between(const Pose& from, const Pose& to, const Eigen::Vector3d& centre);

// One pose's Gauss-Newton system: h = sum w J J^T, g = sum w J r over the pixels it covers with a
// valid observation, w = responsibility of the visible gaussian / sigma^2, r = y - y_hat; objective
// is the log-likelihood of those pixels with the given occlusion map.
struct NormalEquations {
  Matrix6d h = Matrix6d::Zero();
  Vector6d g = Vector6d::Zero();
  double objective = 0;
  int pixels = 0;  // pixels in h (covered, valid, not grazing)
  // The confidence's counts (silhouette_shares): covered pixels with a valid depth, and those of them
  // within config.loss.pixel_sigmas sigma of the surface.
  int measured = 0, visible = 0;
  double visible_share() const { return measured > 0 ? static_cast<double>(visible) / measured : 0.0; }
};

struct RefinedPose {
  Pose pose;
  Matrix6d covariance;  // inverse of h at the pose: camera-frame twist about the centre (m, rad)
  double objective = 0;
  int pixels = 0;
  double visible_share = 0;  // the confidence at the pose (NormalEquations::visible_share)
  int accepted_steps = 0;
  int iterations = 0;  // steps tried (accepted or not), each one rendering of a candidate pose
};

class PoseRefiner {
 public:
  PoseRefiner(const Mesh& mesh, const Camera& camera, const TrackerConfig& config);

  // occlusion: each pixel's occlusion probability for this frame, or empty for none.
  // At the last stage's noise (Refinement::fine_noise_scale when set, else noise_scale).
  NormalEquations normal_equations(const Pose& pose, const DepthImage& depth, std::span<const double> occlusion) const;
  // Up to config.refine.iterations damped steps from start, each kept unless it lowers the
  // log-likelihood (more than rounding could); it stops early when the next step would move no mesh
  // point more than config.refine.converged_motion. With refine.fine_noise_scale, as many again from
  // there at that noise. The result is the last pose kept.
  RefinedPose refine(const Pose& start, const DepthImage& depth, std::span<const double> occlusion) const;
  // The depth the last normal_equations drew, when it drew exactly `pose` (a refined pose whose last
  // step was kept): Rasterizer::render's at that pose, bit for bit. Null otherwise.
  const std::vector<float>* rendering_of(const Pose& pose) const;

 private:
  NormalEquations equations(const TrackerConfig& fit, const Pose& pose, const DepthImage& depth,
                            std::span<const double> occlusion) const;
  // One stage's steps from best (its pose and equations at fit's noise), kept in best.
  void steps(const TrackerConfig& fit, RefinedPose& best, NormalEquations& at_best, const DepthImage& depth,
             std::span<const double> occlusion) const;

  std::vector<TrackerConfig> stages_;  // the fit's configurations (model::fit_config), coarse to fine
  Camera camera_;
  Eigen::Vector3d centre_;
  double radius_;  // largest vertex distance from centre_: how far a rotation moves the mesh
  Rasterizer rasterizer_;
  std::vector<float> planes_;            // per triangle: object-frame unit normal and offset
  mutable std::vector<float> rendered_;  // scratch
  mutable std::vector<int> triangle_ids_;
  mutable std::optional<Pose> rendered_pose_;  // what rendered_ holds
};

// The step the damped system gives: (h + lambda diag(h)) step = g; zero when it is singular.
Vector6d damped_step(const NormalEquations& e, double lambda);

// How far the twist moves a point within radius of the centre, at most: |dt| + radius |dw|.
double step_motion(const Vector6d& step, double radius);

// Levenberg-Marquardt damping after a rejected step: tenfold, and at least 1 (which about halves the
// step), since a silhouette pixel coming or going changes the objective by nats and a step only
// slightly shorter than the rejected one is mostly rejected too. cl/dt_refine.h does the same.
double damping_after_rejection(double lambda);

}  // namespace depthtrack::reference
