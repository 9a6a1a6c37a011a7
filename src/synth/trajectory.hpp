#pragma once
// The ground-truth motion of a synthetic sequence.
#include <depthtrack/pose.hpp>
#include <depthtrack/synth.hpp>

namespace depthtrack::synth {

// camera_from_object at time t (seconds): the mesh's centre (object frame) moves on sinusoids about
// model.centre, the orientation oscillates about a fixed oblique view. Smooth and deterministic.
Pose trajectory_pose(const TrajectoryModel& model, const Eigen::Vector3d& mesh_centre, double t);

}  // namespace depthtrack::synth
