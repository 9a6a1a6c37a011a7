// Weight normalization, degeneracy measures, systematic resampling and the mean pose, by hand.
#include <catch2/catch.hpp>
#include <vector>

#include "reference/pose_mean.hpp"
#include "reference/weights.hpp"

using namespace depthtrack;
using namespace depthtrack::reference;

TEST_CASE("log weights normalize, with ESS and KL from uniform", "[weights]") {
  const std::vector<double> log_w = {-1000.0, -1000.0 + std::log(2.0), -1000.0};  // far below exp's range
  const WeightSummary s = summarize_log_weights(log_w);
  CHECK(s.normalized[0] == Approx(0.25));
  CHECK(s.normalized[1] == Approx(0.5));
  CHECK(s.normalized[2] == Approx(0.25));
  CHECK(s.effective_sample_size == Approx(1.0 / (0.0625 + 0.25 + 0.0625)));
  const double entropy = -(0.5 * std::log(0.25) + 0.5 * std::log(0.5));
  CHECK(s.kl_from_uniform == Approx(std::log(3.0) - entropy));
  // Uniform weights: ESS = N, KL = 0.
  const WeightSummary u = summarize_log_weights(std::vector<double>(8, 3.0));
  CHECK(u.effective_sample_size == Approx(8.0));
  CHECK(u.kl_from_uniform == Approx(0.0).margin(1e-12));
}

TEST_CASE("systematic resampling picks parents by cumulative weight", "[weights]") {
  const std::vector<double> w = {0.1, 0.2, 0.3, 0.4};
  // Positions (0.5 + j) / 4 = 0.125, 0.375, 0.625, 0.875 against cumulative 0.1, 0.3, 0.6, 1.0.
  CHECK(systematic_resample(w, 0.5) == std::vector<int>{1, 2, 3, 3});
  // u = 0: positions 0, 0.25, 0.5, 0.75.
  CHECK(systematic_resample(w, 0.0) == std::vector<int>{0, 1, 2, 3});
  // A zero-weight particle is never chosen.
  CHECK(systematic_resample(std::vector<double>{0.5, 0.0, 0.5}, 0.99) == std::vector<int>{0, 2, 2});
}

TEST_CASE("weighted mean pose averages rotations in the tangent space", "[weights]") {
  const Eigen::Vector3d centre(0, 0, 0.05);
  const double angle = 0.4;
  const Pose a({0.0, 0, 1}, Eigen::Quaterniond(Eigen::AngleAxisd(-angle, Eigen::Vector3d::UnitZ())));
  const Pose b({0.2, 0, 1}, Eigen::Quaterniond(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ())));
  const std::vector<Pose> poses = {a, b};
  const std::vector<double> w = {0.25, 0.75};
  const Pose mean = weighted_mean_pose(poses, w, centre);
  // Tangent mean: 0.25 (-0.4) + 0.75 (0.4) = 0.2 rad about z.
  CHECK(rotation_error(mean, Pose({0, 0, 0}, Eigen::Quaterniond(Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitZ())))) <
        1e-9);
  // The centre is the weighted mean of the centres.
  const Eigen::Vector3d expected_centre = 0.25 * a.apply(centre) + 0.75 * b.apply(centre);
  CHECK((mean.apply(centre) - expected_centre).norm() < 1e-12);
  // Rotations either side of 180 degrees average to 180, not to 0 as component-wise angles would.
  const Pose c({0, 0, 1}, Eigen::Quaterniond(Eigen::AngleAxisd(M_PI - 0.1, Eigen::Vector3d::UnitX())));
  const Pose d({0, 0, 1}, Eigen::Quaterniond(Eigen::AngleAxisd(-(M_PI - 0.1), Eigen::Vector3d::UnitX())));
  const std::vector<Pose> opposite = {c, d};
  const std::vector<double> half = {0.5, 0.5};
  const Pose flip({0, 0, 1}, Eigen::Quaterniond(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX())));
  CHECK(rotation_error(weighted_mean_pose(opposite, half, centre), flip) < 1e-9);
}
