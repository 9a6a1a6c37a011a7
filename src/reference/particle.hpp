#pragma once
// One particle's kinematic state and the motion model that moves it (MODEL.md, "State and motion").
#include <depthtrack/pose.hpp>
#include <depthtrack/tracker.hpp>
#include <depthtrack/tracker_config.hpp>

namespace depthtrack::reference {

struct ParticleState {
  Pose pose;                                                   // camera_from_object
  Eigen::Vector3d linear_velocity = Eigen::Vector3d::Zero();   // m/s, object's local frame
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();  // rad/s, object's local frame
};

// Ornstein-Uhlenbeck step over dt seconds, exact for the velocity: v' = a v + s n with
// a = damping^(dt * rate) and s chosen so that dt = 1/rate gives dbot's sigma per frame. The pose
// then moves by v' dt, in the local frame, about centre (the mesh's centre, object frame).
// normals: six standard normals (linear xyz, angular xyz).
void propagate_particle(ParticleState& s, const MotionModel& m, const Eigen::Vector3d& centre, double dt,
                        const float normals[6]);

// A particle drawn around pose: centre shifted by spread.metres * n[0..2] in the local frame,
// then rotated about the centre by spread.radians * n[3..5]; zero velocity.
ParticleState initial_particle(const Pose& pose, const InitialSpread& spread, const Eigen::Vector3d& centre,
                               const float normals[6]);

// Moves the pose by a local-frame displacement and rotation vector about centre.
Pose move_about_centre(const Pose& pose, const Eigen::Vector3d& centre, const Eigen::Vector3d& displacement,
                       const Eigen::Vector3d& rotation_vector);

}  // namespace depthtrack::reference
