#include "model/particle.hpp"

#include <cmath>

#include "philox.h"

namespace depthtrack::model {

Pose move_about_centre(const Pose& pose, const Eigen::Vector3d& centre, const Eigen::Vector3d& displacement,
                       const Eigen::Vector3d& rotation_vector) {
  const Eigen::Vector3d centre_in_camera = pose.apply(centre) + pose.rotation * displacement;
  const Eigen::Quaterniond rotation = (pose.rotation * rotation_exp(rotation_vector)).normalized();
  return Pose(centre_in_camera - rotation * centre, rotation);
}

MotionStep motion_step(const MotionModel& m, double dt) {
  const double steps = dt * m.reference_rate;  // dt in reference frames
  const double keep = std::pow(m.damping, steps);
  // Stationary variance sigma^2 / (1 - damping^2) per frame; the exact step keeps the share (1 - keep^2).
  const double spread = std::sqrt((1.0 - keep * keep) / (1.0 - m.damping * m.damping));
  return MotionStep{keep, m.sigma_linear * m.reference_rate * spread, m.sigma_angular * m.reference_rate * spread, dt};
}

void propagate_particle(ParticleState& s, const MotionStep& step, const Eigen::Vector3d& centre, const float n[6]) {
  const Eigen::Vector3d w_lin(n[0], n[1], n[2]), w_ang(n[3], n[4], n[5]);
  s.linear_velocity = step.keep * s.linear_velocity + step.linear_std * w_lin;
  s.angular_velocity = step.keep * s.angular_velocity + step.angular_std * w_ang;
  s.pose = move_about_centre(s.pose, centre, s.linear_velocity * step.dt, s.angular_velocity * step.dt);
}

ParticleState initial_particle(const Pose& pose, const InitialSpread& spread, const Eigen::Vector3d& centre,
                               const float n[6]) {
  ParticleState s;
  s.pose = move_about_centre(pose, centre, spread.metres * Eigen::Vector3d(n[0], n[1], n[2]),
                             spread.radians * Eigen::Vector3d(n[3], n[4], n[5]));
  return s;
}

ParticleState draw_initial_particle(std::uint64_t seed, size_t index, std::span<const Pose> modes,
                                    const InitialSpread& spread, const Eigen::Vector3d& centre) {
  float normals[6];
  dt_normals6(seed, static_cast<dt_u32>(index), 0u, DT_STREAM_INIT, normals);
  return initial_particle(modes[index % modes.size()], spread, centre, normals);
}

}  // namespace depthtrack::model
