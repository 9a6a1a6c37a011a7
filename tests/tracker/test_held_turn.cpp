// The reported turn about a mesh's axis of symmetry: filtered in one dimension, held where the depth
// cannot tell it, the rest of the pose left as estimated. Expectations worked by hand from the Kalman
// step in tracker/held_turn.hpp with the default motion model (0.02 rad per frame at 30 Hz: 0.0004 rad^2
// of prior variance a frame).
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <numbers>

#include "tracker/held_turn.hpp"

using namespace depthtrack;

namespace {
constexpr double kDegree = std::numbers::pi / 180;
constexpr double kFrame = 1.0 / 30;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kManyPixels = 100;  // seen pixels: half of them (share 0.5) break the symmetry

SymmetryAxis z_axis_through(const Eigen::Vector3d& point, double share) {
  SymmetryAxis axis;
  axis.point = point;
  axis.direction = Eigen::Vector3d::UnitZ();
  axis.share = share;
  return axis;
}

Eigen::Quaterniond about(const Eigen::Vector3d& axis, double degrees) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(degrees * kDegree, axis));
}

// The estimate: a swing of 2 degrees about x, then `turn` degrees about the object's z, placed at t.
Pose estimate_with_turn(double turn) {
  return Pose(Eigen::Vector3d(0.1, -0.05, 0.8),
              about(Eigen::Vector3d::UnitX(), 2) * about(Eigen::Vector3d::UnitZ(), turn));
}

void check_same_rotation(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  CHECK(a.angularDistance(b) == Approx(0).margin(1e-9));
}
}  // namespace

TEST_CASE("the turn about the axis is weighed against the last report's, the rest of the pose kept", "[tracker]") {
  const Eigen::Vector3d point(0.01, 0.02, 0);
  HeldTurn held(z_axis_through(point, 0.5), MotionModel{});
  const Pose first = estimate_with_turn(0);
  const Pose reported_first = held.report(first, 0.01, kManyPixels, 0);
  check_same_rotation(reported_first.rotation, first.rotation);  // nothing before it: as estimated
  CHECK((reported_first.translation - first.translation).norm() == Approx(0).margin(1e-12));

  // Prior 0.01 + 0.0004 = 0.0104 against the estimate's 0.0104: gain 1/2, so 10 degrees become 5.
  const Pose second = estimate_with_turn(10);
  const Pose reported = held.report(second, 0.0104, kManyPixels, kFrame);
  check_same_rotation(reported.rotation, estimate_with_turn(5).rotation);
  // Turned about the axis through `point`: that point and the axis' direction stay where the estimate puts them.
  CHECK((reported.apply(point) - second.apply(point)).norm() == Approx(0).margin(1e-12));
  CHECK((reported.rotation * Eigen::Vector3d::UnitZ() - second.rotation * Eigen::Vector3d::UnitZ()).norm() ==
        Approx(0).margin(1e-12));
  // A point off the axis does move: 0.05 m out, turned by -5 degrees about it.
  const Eigen::Vector3d off = point + Eigen::Vector3d(0.05, 0, 0);
  CHECK((reported.apply(off) - second.apply(off)).norm() == Approx(2 * 0.05 * std::sin(2.5 * kDegree)));

  // Posterior 0.0052, prior 0.0056 against 0.0056: gain 1/2 again, the 5 degrees left become 2.5 more.
  const Pose third = held.report(second, 0.0056, kManyPixels, 2 * kFrame);
  check_same_rotation(third.rotation, estimate_with_turn(7.5).rotation);
}

TEST_CASE("a turn the depth cannot tell is held, the swing still followed", "[tracker]") {
  // Swung 3 degrees about the object's y (across the axis), turned 20 about its z, moved 2 mm.
  const Pose first = estimate_with_turn(0);
  Pose swung = first;
  swung.rotation = first.rotation * about(Eigen::Vector3d::UnitY(), 3) * about(Eigen::Vector3d::UnitZ(), 20);
  swung.translation += Eigen::Vector3d(0.002, 0, 0);
  const Pose held_rotation(first.translation, first.rotation * about(Eigen::Vector3d::UnitY(), 3));

  SECTION("no variance: the covariance leaves the turn undetermined") {
    HeldTurn held(z_axis_through(Eigen::Vector3d::Zero(), 0.5), MotionModel{});
    held.report(first, 0.01, kManyPixels, 0);
    const Pose reported = held.report(swung, kInf, kManyPixels, kFrame);
    check_same_rotation(reported.rotation, held_rotation.rotation);
    CHECK((reported.translation - swung.translation).norm() == Approx(0).margin(1e-12));  // axis through the origin
  }
  SECTION("a mesh symmetric to its last percent: whatever the fit's variance says") {
    HeldTurn held(z_axis_through(Eigen::Vector3d::Zero(), 1.0), MotionModel{});
    held.report(first, 1e-6, 1e6, 0);
    check_same_rotation(held.report(swung, 1e-6, 1e6, kFrame).rotation, held_rotation.rotation);
  }
  SECTION("too few seen pixels break the symmetry: (1 - 0.9) x 39 < 4") {
    HeldTurn held(z_axis_through(Eigen::Vector3d::Zero(), 0.9), MotionModel{});
    held.report(first, 1e-6, 39, 0);
    check_same_rotation(held.report(swung, 1e-6, 39, kFrame).rotation, held_rotation.rotation);
    // 41 seen pixels (4.1 of them breaking it) tell it: a variance far below the prior's is followed.
    check_same_rotation(held.report(swung, 1e-9, 41, 2 * kFrame).rotation, swung.rotation);
  }
}

TEST_CASE("without a fit the estimate is reported and the filter starts again from it", "[tracker]") {
  HeldTurn held(z_axis_through(Eigen::Vector3d::Zero(), 0.5), MotionModel{});
  held.report(estimate_with_turn(0), 0.01, kManyPixels, 0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  check_same_rotation(held.report(estimate_with_turn(30), nan, kManyPixels, kFrame).rotation,
                      estimate_with_turn(30).rotation);
  // Started again from the 30 degrees with the next estimate's own variance: it is reported as it is.
  check_same_rotation(held.report(estimate_with_turn(40), 0.01, kManyPixels, 2 * kFrame).rotation,
                      estimate_with_turn(40).rotation);
  // And after a reset likewise.
  held.reset();
  check_same_rotation(held.report(estimate_with_turn(-50), kInf, kManyPixels, 3 * kFrame).rotation,
                      estimate_with_turn(-50).rotation);
}

TEST_CASE("the turn's variance from the covariance's rotation block", "[tracker]") {
  Eigen::Matrix<double, 6, 6> c = Eigen::Matrix<double, 6, 6>::Zero();
  c.diagonal() << 1, 1, 1, 0.04, 0.09, 0.16;
  c(3, 4) = c(4, 3) = 0.01;
  CHECK(turn_variance(c, Eigen::Vector3d::UnitZ()) == Approx(0.16));
  // (1, 1, 0) / sqrt 2: (0.04 + 0.09 + 2 x 0.01) / 2.
  CHECK(turn_variance(c, Eigen::Vector3d(1, 1, 0).normalized()) == Approx(0.075));
  // An axis set apart counts where the turn involves it, not elsewhere.
  c(5, 5) = kInf;
  CHECK(std::isinf(turn_variance(c, Eigen::Vector3d(0, 0.6, 0.8))));
  CHECK(turn_variance(c, Eigen::Vector3d::UnitY()) == Approx(0.09));
  c(3, 3) = std::numeric_limits<double>::quiet_NaN();
  CHECK(std::isnan(turn_variance(c, Eigen::Vector3d::UnitY())));
}
