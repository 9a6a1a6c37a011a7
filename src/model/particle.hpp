#pragma once
// One particle's kinematic state, the motion model that moves it and the initial draw around a pose
// (MODEL.md, "State and motion"): the reference filter runs these in double; the device filter's
// kernels (cl/propagate.cl, cl/initialize.cl) run the same steps in float from the same constants.
#include <depthtrack/initial_spread.hpp>
#include <depthtrack/pose.hpp>
#include <depthtrack/tracker_config.hpp>
#include <span>

namespace depthtrack::model {

struct ParticleState {
  Pose pose;                                                   // camera_from_object
  Eigen::Vector3d linear_velocity = Eigen::Vector3d::Zero();   // m/s, object's local frame
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();  // rad/s, object's local frame
};

// The Ornstein-Uhlenbeck step over dt seconds, exact for the velocity: v' = keep v + std n with
// keep = damping^(dt * rate) and std chosen so that dt = 1/rate gives dbot's sigma per frame.
// Computed once per frame, for every particle and every backend.
struct MotionStep {
  double keep;         // share of the velocity kept
  double linear_std;   // m/s added per unit normal
  double angular_std;  // rad/s added per unit normal
  double dt;           // seconds
};
MotionStep motion_step(const MotionModel& m, double dt);

// Velocity step, then the pose moves by v' dt, in the local frame, about centre (the mesh's centre,
// object frame). normals: six standard normals (linear xyz, angular xyz).
void propagate_particle(ParticleState& s, const MotionStep& step, const Eigen::Vector3d& centre,
                        const float normals[6]);

// A particle drawn around pose: centre shifted by spread.metres * n[0..2] in the local frame,
// then rotated about the centre by spread.radians * n[3..5]; zero velocity.
ParticleState initial_particle(const Pose& pose, const InitialSpread& spread, const Eigen::Vector3d& centre,
                               const float normals[6]);
// Particle `index` of a cloud drawn around modes (around modes[index % modes.size()]) with the
// normals of (seed, index, frame 0, DT_STREAM_INIT): the draw cl/initialize.cl makes on the device.
ParticleState draw_initial_particle(std::uint64_t seed, size_t index, std::span<const Pose> modes,
                                    const InitialSpread& spread, const Eigen::Vector3d& centre);

// Moves the pose by a local-frame displacement and rotation vector about centre.
Pose move_about_centre(const Pose& pose, const Eigen::Vector3d& centre, const Eigen::Vector3d& displacement,
                       const Eigen::Vector3d& rotation_vector);

}  // namespace depthtrack::model
