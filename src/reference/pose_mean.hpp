#pragma once
// Weighted mean of poses: positions of the mesh's centre averaged in space, rotations averaged in
// the tangent space of a reference rotation (iterated, the Karcher mean), never as Euler angles.
#include <depthtrack/pose.hpp>
#include <span>

namespace depthtrack::reference {

// poses and weights have one entry per particle; weights sum to 1. The reference rotation is
// the heaviest pose's. centre is the mesh's centre in the object frame.
Pose weighted_mean_pose(std::span<const Pose> poses, std::span<const double> weights, const Eigen::Vector3d& centre);

}  // namespace depthtrack::reference
