#pragma once
// Weighted mean of poses: positions of the mesh's centre averaged in space, rotations averaged in
// the tangent space of a reference rotation (iterated, the Karcher mean), never as Euler angles.
#include <depthtrack/pose.hpp>
#include <span>

#include "core/thread_pool.hpp"

namespace depthtrack::reference {

// poses and weights have one entry per particle; weights sum to 1. The reference rotation is
// the heaviest pose's. centre is the mesh's centre in the object frame. With a pool, each particle's
// terms are computed on its threads and summed in particle order on the caller's: the same mean, bit
// for bit.
Pose weighted_mean_pose(std::span<const Pose> poses, std::span<const double> weights, const Eigen::Vector3d& centre,
                        ThreadPool* pool = nullptr);

}  // namespace depthtrack::reference
