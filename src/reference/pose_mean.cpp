#include "reference/pose_mean.hpp"

#include <algorithm>
#include <vector>

namespace depthtrack::reference {

namespace {

// f(first, last) over [0, n) in the pool's ranges (run_ranges); without a pool, once on the caller's.
template <typename F>
void over_ranges(ThreadPool* pool, size_t n, F&& f) {
  if (!pool) return f(size_t{0}, n);
  run_ranges(*pool, n, [&](size_t, size_t first, size_t last, int) { f(first, last); });
}

// The sum of the terms in index order, as a sequential loop adds them.
Eigen::Vector3d sum_in_order(const std::vector<Eigen::Vector3d>& terms) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& t : terms) sum += t;
  return sum;
}

}  // namespace

Pose weighted_mean_pose(std::span<const Pose> poses, std::span<const double> weights, const Eigen::Vector3d& centre,
                        ThreadPool* pool) {
  std::vector<Eigen::Vector3d> terms(poses.size());
  over_ranges(pool, poses.size(), [&](size_t first, size_t last) {
    for (size_t i = first; i < last; ++i) terms[i] = weights[i] * poses[i].apply(centre);
  });
  const Eigen::Vector3d mean_centre = sum_in_order(terms);
  const size_t heaviest = static_cast<size_t>(std::max_element(weights.begin(), weights.end()) - weights.begin());
  Eigen::Quaterniond mean = poses[heaviest].rotation;
  for (int iteration = 0; iteration < 4; ++iteration) {
    const Eigen::Quaterniond inverse = mean.conjugate();
    over_ranges(pool, poses.size(), [&](size_t first, size_t last) {
      for (size_t i = first; i < last; ++i) terms[i] = weights[i] * rotation_log(inverse * poses[i].rotation);
    });
    mean = (mean * rotation_exp(sum_in_order(terms))).normalized();
  }
  return Pose(mean_centre - mean * centre, mean);
}

}  // namespace depthtrack::reference
