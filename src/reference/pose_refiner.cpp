#include "reference/pose_refiner.hpp"

#include <Eigen/Cholesky>
#include <cmath>

#include "atlas/triangle_planes.hpp"
#include "model/fit_noise.hpp"
#include "reference/observation_model.hpp"

namespace depthtrack::reference {

bool depth_jacobian(const Eigen::Vector3d& point, const Eigen::Vector3d& normal, const Eigen::Vector3d& ray,
                    const Eigen::Vector3d& centre, double min_incidence, Vector6d& row) {
  const double incidence = normal.dot(ray);
  if (std::abs(incidence) < min_incidence * ray.norm()) return false;
  row.head<3>() = normal / incidence;
  row.tail<3>() = (point - centre).cross(normal) / incidence;
  return true;
}

Pose apply_twist(const Pose& pose, const Eigen::Vector3d& centre, const Vector6d& twist) {
  const Eigen::Vector3d moved_centre = pose.apply(centre) + twist.head<3>();
  const Eigen::Quaterniond rotation = (rotation_exp(twist.tail<3>()) * pose.rotation).normalized();
  return Pose(moved_centre - rotation * centre, rotation);
}

Vector6d twist_between(const Pose& from, const Pose& to, const Eigen::Vector3d& centre) {
  Vector6d twist;
  twist.head<3>() = to.apply(centre) - from.apply(centre);
  twist.tail<3>() = rotation_log(to.rotation * from.rotation.conjugate());
  return twist;
}

Vector6d damped_step(const NormalEquations& e, double lambda) {
  Matrix6d a = e.h;
  a.diagonal() *= 1.0 + lambda;
  const Eigen::LDLT<Matrix6d> solver(a);
  if (solver.info() != Eigen::Success || !solver.isPositive() || e.pixels < 6) return Vector6d::Zero();
  const Vector6d step = solver.solve(e.g);
  return step.allFinite() ? step : Vector6d::Zero();
}

double step_motion(const Vector6d& step, double radius) {
  return step.head<3>().norm() + radius * step.tail<3>().norm();
}

double damping_after_rejection(double lambda) {
  return std::max(10.0 * lambda, 1.0);
}

PoseRefiner::PoseRefiner(const Mesh& mesh, const Camera& camera, const TrackerConfig& config)
    : stages_(model::fit_stages(config)),  // the fit's own noise (Refinement::noise_scale), then fine_noise_scale's
      camera_(camera),
      centre_(mesh.centre().cast<double>()),
      radius_(mesh.radius()),
      rasterizer_(mesh, camera, config.near_plane, config.observation.max_depth),
      planes_(render::triangle_planes(mesh)),
      rendered_(static_cast<size_t>(camera.pixel_count())),
      triangle_ids_(static_cast<size_t>(camera.pixel_count())) {}

NormalEquations PoseRefiner::normal_equations(const Pose& pose, const DepthImage& depth,
                                              std::span<const double> occlusion) const {
  return equations(stages_.back(), pose, depth, occlusion);
}

NormalEquations PoseRefiner::equations(const TrackerConfig& fit, const Pose& pose, const DepthImage& depth,
                                       std::span<const double> occlusion) const {
  NormalEquations e;
  rendered_pose_.reset();  // until the rendering is done
  const PixelBox box = rasterizer_.render(pose, rendered_, triangle_ids_);
  rendered_pose_ = pose;
  const Eigen::Matrix3d rotation = pose.rotation.toRotationMatrix();
  const Eigen::Vector3d centre = pose.apply(centre_);
  const ObservationModel& m = fit.observation;
  const double tail = m.tail_weight / m.max_depth;
  for (int v = box.v0; v < box.v1; ++v) {
    for (int u = box.u0; u < box.u1; ++u) {
      const size_t k = static_cast<size_t>(v) * static_cast<size_t>(camera_.width) + static_cast<size_t>(u);
      const double y_hat = rendered_[k], y = depth.data()[k];
      if (y_hat <= 0 || !DepthImage::is_valid(static_cast<float>(y))) continue;
      ++e.measured;
      e.visible += band_side(m, fit.loss.pixel_sigmas, y, y_hat) == BandSide::Within;
      const double p = occlusion.empty() ? 0.0 : occlusion[k];
      const PixelDensities d = pixel_densities(m, y, y_hat);
      e.objective += pixel_log_ratio(d, p);
      // E-step: the share of this pixel's density that the visible gaussian explains.
      const double responsibility = (1.0 - p) * (d.visible - tail) / ((1.0 - p) * d.visible + p * d.occluded);
      const double sigma = depth_sigma(m, y);
      const float* plane = &planes_[4 * static_cast<size_t>(triangle_ids_[k])];
      const Eigen::Vector3d normal = rotation * Eigen::Vector3d(plane[0], plane[1], plane[2]);
      const Eigen::Vector3d ray((u - camera_.cx) / camera_.fx, (v - camera_.cy) / camera_.fy, 1.0);
      Vector6d row;
      if (!depth_jacobian(y_hat * ray, normal, ray, centre, fit.refine.min_incidence, row)) continue;
      const double w = responsibility / (sigma * sigma);
      e.h.selfadjointView<Eigen::Lower>().rankUpdate(row, w);
      e.g += (w * (y - y_hat)) * row;
      ++e.pixels;
    }
  }
  e.h = e.h.selfadjointView<Eigen::Lower>();
  return e;
}

const std::vector<float>* PoseRefiner::rendering_of(const Pose& pose) const {
  const bool same = rendered_pose_ && rendered_pose_->translation == pose.translation &&
                    rendered_pose_->rotation.coeffs() == pose.rotation.coeffs();
  return same ? &rendered_ : nullptr;
}

void PoseRefiner::steps(const TrackerConfig& fit, RefinedPose& best, NormalEquations& at_best, const DepthImage& depth,
                        std::span<const double> occlusion) const {
  double lambda = fit.refine.damping;
  // A step is kept unless it lowers the log-likelihood by more than float rounding could (the device's).
  const double tolerance = model::step_tolerance(fit.refine.noise_scale);
  for (int iteration = 0; iteration < fit.refine.iterations; ++iteration) {
    const Vector6d step = damped_step(at_best, lambda);
    if (step.isZero() || step_motion(step, radius_) < fit.refine.converged_motion) break;
    ++best.iterations;
    const Pose candidate = apply_twist(best.pose, centre_, step);
    const NormalEquations at_candidate = equations(fit, candidate, depth, occlusion);
    if (at_candidate.objective >= at_best.objective - tolerance) {
      best.pose = candidate;
      at_best = at_candidate;
      lambda = fit.refine.damping;
      ++best.accepted_steps;
    } else {
      lambda = damping_after_rejection(lambda);  // lean towards gradient descent
    }
  }
}

RefinedPose PoseRefiner::refine(const Pose& start, const DepthImage& depth, std::span<const double> occlusion) const {
  RefinedPose best;
  best.pose = start;
  NormalEquations at_best;
  for (const TrackerConfig& fit : stages_) {
    at_best = equations(fit, best.pose, depth, occlusion);
    steps(fit, best, at_best, depth, occlusion);
  }
  best.objective = at_best.objective;
  best.pixels = at_best.pixels;
  best.visible_share = at_best.visible_share();
  best.covariance = model::fit_covariance(at_best.h, at_best.pixels, radius_, stages_.back().refine);
  return best;
}

}  // namespace depthtrack::reference
