// How far the reported covariance holds (eval/covariance_coverage): the error twist, the Mahalanobis
// check and the coverage share on hand-made cases and on draws from a known Gaussian; then, end to end,
// the share of a tracked synthetic sequence's frames whose error lies inside the reported 95 % region.
#include <Eigen/Cholesky>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <depthtrack/error.hpp>
#include <depthtrack/evaluation.hpp>
#include <depthtrack/synth.hpp>
#include <limits>
#include <random>

#include "eval/covariance_coverage.hpp"
#include "model/covariance_calibration.hpp"
#include "support.hpp"

using namespace depthtrack;
using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Vector6d = Eigen::Matrix<double, 6, 1>;

TEST_CASE("the error twist is the centre's displacement and the rotation vector of R_est R_truth^T", "[coverage]") {
  const Eigen::Vector3d centre(0.0, 0.0, 0.1);
  const Pose truth(Eigen::Vector3d(0.0, 0.0, 1.0), Eigen::Quaterniond::Identity());
  // Turned by 0.1 rad about the camera's x axis and moved by 1 cm along y.
  const Eigen::Quaterniond turn(Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitX()));
  const Pose estimate(Eigen::Vector3d(0.0, 0.01, 1.0), turn);
  const Vector6d e = pose_error_twist(estimate, truth, centre);
  // The centre, (0, 0, 0.1) in the object, lands at (0, 0.01 - 0.1 sin 0.1, 1 + 0.1 cos 0.1) against (0, 0, 1.1).
  CHECK(e(0) == Approx(0.0).margin(1e-12));
  CHECK(e(1) == Approx(0.01 - 0.1 * std::sin(0.1)));
  CHECK(e(2) == Approx(0.1 * std::cos(0.1) - 0.1));
  CHECK(e(3) == Approx(0.1));
  CHECK(e(4) == Approx(0.0).margin(1e-12));
  CHECK(e(5) == Approx(0.0).margin(1e-12));
}

TEST_CASE("the covariance check leaves undetermined axes out and compares with the chi-squared quantile",
          "[coverage]") {
  CHECK(chi2_95(1) == Approx(3.841459));
  CHECK(chi2_95(3) == Approx(7.814728));
  CHECK(chi2_95(6) == Approx(12.591587));
  CHECK_THROWS_AS(chi2_95(0), InputError);
  CHECK_THROWS_AS(chi2_95(7), InputError);

  constexpr double inf = std::numeric_limits<double>::infinity();
  Matrix6d sigma = Matrix6d::Zero();
  sigma.diagonal() << 1e-6, 4e-6, inf, 1e-4, 1e-4, inf;  // 1 mm, 2 mm, free, 0.01 rad, 0.01 rad, free
  Vector6d e;
  e << 0.002, 0.002, 5.0, 0.01, 0.0, 3.0;  // the free axes' errors are huge and do not count
  auto check = check_covariance(e, sigma);
  REQUIRE(check);
  CHECK(check->dof == 4);
  CHECK(check->d2 == Approx(4.0 + 1.0 + 1.0 + 0.0));  // (2/1)^2 + (2/2)^2 + (0.01/0.01)^2
  CHECK(check->inside);                               // 6 <= 9.488
  e(4) = 0.02;                                        // + (0.02/0.01)^2 = 10 > 9.488
  check = check_covariance(e, sigma);
  REQUIRE(check);
  CHECK(check->d2 == Approx(10.0));
  CHECK_FALSE(check->inside);
  // Each axis on its own: e_i^2 / Sigma_ii, none for the free axes.
  CHECK(check->axis_d2[0] == Approx(4.0));  // (2 mm / 1 mm)^2
  CHECK(check->axis_d2[1] == Approx(1.0));  // (2 mm / 2 mm)^2
  CHECK(std::isnan(check->axis_d2[2]));
  CHECK(check->axis_d2[3] == Approx(1.0));  // (0.01 / 0.01)^2
  CHECK(check->axis_d2[4] == Approx(4.0));  // (0.02 / 0.01)^2
  CHECK(std::isnan(check->axis_d2[5]));

  // A correlation: for 1e-6 [[1, 0.5], [0.5, 1]] the error (1, -1) mm has d2 = 2 / (1 - 0.5) = 4.
  Matrix6d correlated = Matrix6d::Zero();
  correlated.diagonal() << 1e-6, 1e-6, inf, inf, inf, inf;
  correlated(0, 1) = correlated(1, 0) = 0.5e-6;
  check = check_covariance((Vector6d() << 1e-3, -1e-3, 0, 0, 0, 0).finished(), correlated);
  REQUIRE(check);
  CHECK(check->dof == 2);
  CHECK(check->d2 == Approx(4.0));
  CHECK(check->inside);  // 4 <= 5.991
  // Each axis alone sees 1 mm at 1 mm: 1, where the pair, against its correlation, is 4.
  CHECK(check->axis_d2[0] == Approx(1.0));
  CHECK(check->axis_d2[1] == Approx(1.0));

  CHECK_FALSE(check_covariance(e, Matrix6d::Constant(std::nan(""))));  // refinement off
  CHECK_FALSE(check_covariance(e, Matrix6d::Identity() * inf));        // nothing determined
  CHECK_FALSE(check_covariance(e, -Matrix6d::Identity()));             // not positive definite
  // A variance of kDeterminedBelow (1 m^2 or rad^2) or more is undetermined: that axis counts no freedom.
  Matrix6d wide = Matrix6d::Identity() * 1e-6;
  wide(5, 5) = model::kDeterminedBelow;
  check = check_covariance((Vector6d() << 1e-3, 0, 0, 0, 0, 0.5).finished(), wide);
  REQUIRE(check);
  CHECK(check->dof == 5);
  CHECK(check->d2 == Approx(1.0));
  CHECK(check->axis_d2[0] == Approx(1.0));
  CHECK(check->axis_d2[1] == Approx(0.0).margin(1e-12));
  CHECK(std::isnan(check->axis_d2[5]));  // its variance is kDeterminedBelow: not determined
}

TEST_CASE("coverage is the share inside with its Wilson interval", "[coverage]") {
  std::vector<CovarianceCheck> checks(20, CovarianceCheck{1.0, 3, true});
  checks[7].inside = false;
  const Coverage c = coverage(checks);
  CHECK(c.checked == 20);
  CHECK(c.inside == 19);
  CHECK(c.share == Approx(0.95));
  CHECK(c.low == Approx(0.76387).epsilon(1e-4));  // Wilson score interval, z = 1.96, worked by hand
  CHECK(c.high == Approx(0.99112).epsilon(1e-4));
  CHECK(coverage({}).checked == 0);
  CHECK(std::isnan(coverage({}).share));
}

TEST_CASE("errors drawn from the covariance itself land in its 95 % region 95 % of the time", "[coverage]") {
  // A full, correlated covariance with one undetermined axis; 4000 draws: the share's standard deviation
  // is sqrt(0.95 0.05 / 4000) = 0.0034, so 0.94-0.96 is about 3 of them either side.
  Matrix6d a;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) a(i, j) = std::sin(1.7 * i + 0.9 * j * j + 0.4) + (i == j ? 2.0 : 0.0);
  Matrix6d sigma = 1e-6 * a * a.transpose();
  const Eigen::LLT<Matrix6d> llt(sigma);
  REQUIRE(llt.info() == Eigen::Success);
  const Matrix6d l = llt.matrixL();
  std::mt19937_64 rng(5);
  std::normal_distribution<double> normal;
  std::vector<CovarianceCheck> checks, free_axis;
  Matrix6d with_free = sigma;  // axis 2 set apart; the other five keep their block, the draws' marginal
  with_free.row(2).setZero();
  with_free.col(2).setZero();
  with_free(2, 2) = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 4000; ++k) {
    Vector6d z;
    for (int i = 0; i < 6; ++i) z(i) = normal(rng);
    const Vector6d e = l * z;
    checks.push_back(*check_covariance(e, sigma));
    free_axis.push_back(*check_covariance(e, with_free));
  }
  CHECK(coverage(checks).share == Approx(0.95).margin(0.01));
  CHECK(checks.front().dof == 6);
  CHECK(coverage(free_axis).share == Approx(0.95).margin(0.01));
  CHECK(free_axis.front().dof == 5);
  // The same draws against a covariance a quarter as wide (half the standard deviation): far fewer inside.
  std::vector<CovarianceCheck> narrow;
  for (int k = 0; k < 200; ++k) {
    Vector6d z;
    for (int i = 0; i < 6; ++i) z(i) = normal(rng);
    narrow.push_back(*check_covariance(l * z, sigma / 4.0));
  }
  CHECK(coverage(narrow).share < 0.5);  // chi2_6 below 12.59 / 4 = 3.15: 21 %
}

TEST_CASE("on a synthetic structured-light sequence the 95 % region holds the true error", "[coverage][tracking]") {
  // The built-in object over 40 frames (160x120 sensor, tracked at 80x60 by the reference backend) from
  // ground truth moved by 1 cm / 5 degrees. Measured: 38 of 40 inside, median d2 / dof 0.52. Frames
  // follow one another, so they are not independent draws, and the bounds are loose for that: at least
  // 80 % inside (32 of 40), and a region not vacuously wide: the median d2 / dof at least 0.2 (a Gaussian
  // error gives about 0.9; the fit's covariance before the residual's scale, wide for this sensor's
  // noise, gave under 0.1 on the structured-light handset).
  SynthConfig c;
  c.camera = Camera::make(160, 120, 131.25, 131.25, 79.75, 59.75);
  c.frames = 40;
  const Mesh mesh = builtin_demo_mesh();
  const Sequence sequence = write_synthetic_sequence(test::temp_dir("coverage_synthetic") / "seq", mesh, c);
  TrackerConfig config;
  config.backend = "reference";
  const Eigen::Vector3d centre = mesh.centre().cast<double>();
  const Pose start = perturb_pose(*sequence.frames.front().ground_truth, centre, 0.01, 5.0, 1);
  const auto frames = track_sequence(sequence, mesh, config, start, InitialSpread{});
  std::vector<CovarianceCheck> checks;
  std::vector<double> ratios;
  for (const TrackedFrame& f : frames) {
    REQUIRE(f.ground_truth);
    const auto check =
        check_covariance(pose_error_twist(f.estimate.pose, *f.ground_truth, centre), f.estimate.covariance);
    REQUIRE(check);
    checks.push_back(*check);
    ratios.push_back(check->d2 / check->dof);
  }
  const Coverage cover = coverage(checks);
  std::nth_element(ratios.begin(), ratios.begin() + static_cast<long>(ratios.size() / 2), ratios.end());
  const double median = ratios[ratios.size() / 2];
  std::printf("synthetic coverage: %zu of %zu inside the 95 %% region, median d2/dof %.3f\n", cover.inside,
              cover.checked, median);
  CHECK(cover.checked == 40);
  CHECK(cover.share >= 0.8);
  CHECK(median >= 0.2);
}

TEST_CASE("a turn about a tilted axis left undetermined: any turn about it, and 95 % of the rest, inside",
          "[coverage]") {
  // Errors drawn from sigma plus a turn of up to 30 degrees about the axis (0, 0.6, 0.8) through a point
  // 1 cm off the centre: the check leaves that direction out and counts 5 degrees of freedom.
  Matrix6d a;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) a(i, j) = std::cos(0.8 * i + 1.1 * j + 0.2) + (i == j ? 2.0 : 0.0);
  const Matrix6d sigma = 1e-6 * a * a.transpose();
  const Eigen::Vector3d axis(0, 0.6, 0.8), offset(0.01, 0, 0);
  Vector6d turn;
  turn << axis.cross(offset), axis;
  const Matrix6d reported = model::with_undetermined_direction(sigma, turn);
  const Matrix6d l = Eigen::LLT<Matrix6d>(sigma).matrixL();
  std::mt19937_64 rng(11);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> angle(-0.52, 0.52);
  std::vector<CovarianceCheck> checks, unaware;
  for (int k = 0; k < 4000; ++k) {
    Vector6d z;
    for (int i = 0; i < 6; ++i) z(i) = normal(rng);
    const Vector6d e = l * z + angle(rng) * turn;
    checks.push_back(*check_covariance(e, reported));
    unaware.push_back(*check_covariance(e, sigma));
  }
  CHECK(checks.front().dof == 5);
  CHECK(coverage(checks).share == Approx(0.95).margin(0.01));
  CHECK(coverage(unaware).share < 0.2);  // the same errors against sigma alone: the turn is far outside
}

TEST_CASE("a covariance that determines nothing has no region, counted apart", "[coverage]") {
  Vector6d e = Vector6d::Constant(1e-3);
  CHECK_FALSE(check_covariance(e, model::undetermined_covariance()));
  const Coverage c = coverage({CovarianceCheck{1.0, 6, true}}, 3);
  CHECK(c.checked == 1);
  CHECK(c.no_region == 3);
  CHECK(c.share == 1.0);
}
