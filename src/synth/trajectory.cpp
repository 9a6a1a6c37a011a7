#include "synth/trajectory.hpp"

#include <numbers>

namespace depthtrack::synth {

namespace {
// Frequency multipliers of the slowest period per axis: incommensurate, so the path never repeats
// within a sequence and the axes do not move in lockstep.
const Eigen::Vector3d kTranslationRate{1.0, 1.3, 1.7};
const Eigen::Vector3d kRotationRate{1.7, 1.0, 1.3};
// Phases away from pi/2 and 3pi/2: at t = 0 every component is moving, none sits at a turning point.
const Eigen::Vector3d kTranslationPhase{0.4, 2.0, 3.9};
const Eigen::Vector3d kRotationPhase{1.1, 5.3, 2.7};

// Sinusoid per axis: amplitude * sin(2 pi rate t / period + phase).
Eigen::Vector3d oscillation(const Eigen::Vector3d& amplitude, const Eigen::Vector3d& rate, const Eigen::Vector3d& phase,
                            double period, double t) {
  Eigen::Vector3d out;
  for (int k = 0; k < 3; ++k)
    out[k] = amplitude[k] * std::sin(2.0 * std::numbers::pi * rate[k] * t / period + phase[k]);
  return out;
}

// An oblique view: turned 0.6 rad about the camera's y axis and tilted 0.7 rad about x, so the camera
// sees a top face (with the demo mesh's handle), a front face and an end face at once.
Eigen::Quaterniond base_orientation() {
  return Eigen::Quaterniond(Eigen::AngleAxisd(0.6, Eigen::Vector3d::UnitY()) *
                            Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitX()));
}
}  // namespace

Pose trajectory_pose(const TrajectoryModel& model, const Eigen::Vector3d& mesh_centre, double t) {
  // Right-multiplied: the oscillation is about the object's own axes.
  const Eigen::Quaterniond rotation =
      base_orientation() *
      rotation_exp(oscillation(model.rotation_amplitude, kRotationRate, kRotationPhase, model.period, t));
  const Eigen::Vector3d centre_in_camera =
      model.centre + oscillation(model.amplitude, kTranslationRate, kTranslationPhase, model.period, t);
  return Pose(centre_in_camera - rotation * mesh_centre, rotation);
}

}  // namespace depthtrack::synth
