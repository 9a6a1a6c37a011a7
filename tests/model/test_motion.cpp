// The motion model over real time steps, by hand.
#include <catch2/catch.hpp>

#include "model/particle.hpp"

using namespace depthtrack;
using namespace depthtrack::model;

namespace {
const Eigen::Vector3d centre(0.01, 0.02, -0.03);
const Pose start({0.1, 0.0, 0.8}, Eigen::Quaterniond(Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitY())));
}  // namespace

TEST_CASE("one 1/30 s step is dbot's per-frame form", "[motion]") {
  const MotionModel m;
  ParticleState s{start, {0.3, 0, 0}, {0, 0, 0}};  // 0.3 m/s along local x
  const float n[6] = {1, 0, 0, 0, 0, 0};
  propagate_particle(s, motion_step(m, 1.0 / 30), centre, n);
  // v' = 0.8 v + sigma_lin * 30 * n (per-frame sigma 2.5 mm -> 0.075 m/s)
  CHECK(s.linear_velocity.x() == Approx(0.8 * 0.3 + 0.075));
  // The centre moves by v' / 30 along the object's x axis; the orientation is unchanged.
  const Eigen::Vector3d moved = s.pose.apply(centre) - start.apply(centre);
  const Eigen::Vector3d expected = start.rotation * Eigen::Vector3d(0.8 * 0.3 / 30 + 0.0025, 0, 0);
  CHECK((moved - expected).norm() < 1e-12);
  CHECK(rotation_error(s.pose, start) < 1e-12);
}

TEST_CASE("a dropped frame widens the spread exactly as two steps would", "[motion]") {
  const MotionModel m;
  ParticleState s{start, {0, 0, 0}, {0, 0, 0}};
  const float n[6] = {0, 0, 0, 1, 0, 0};
  propagate_particle(s, motion_step(m, 2.0 / 30), centre, n);
  // Two frames from rest: variance (0.8^2 + 1) sigma^2 = 1.64 sigma^2, so one unit normal gives
  // sqrt(1.64) * 0.02 rad/frame = sqrt(1.64) * 0.6 rad/s.
  CHECK(s.angular_velocity.x() == Approx(std::sqrt(1.64) * 0.6));
  // Rotation about the centre: the centre stays where it was.
  CHECK((s.pose.apply(centre) - start.apply(centre)).norm() < 1e-12);
  CHECK(rotation_error(s.pose, start) == Approx(std::sqrt(1.64) * 0.6 * 2.0 / 30));
}

TEST_CASE("velocity decays with the real time step and no noise", "[motion]") {
  const MotionModel m;
  ParticleState s{start, {0, 0.2, 0}, {0, 0, 0.3}};
  const float zero[6] = {0, 0, 0, 0, 0, 0};
  propagate_particle(s, motion_step(m, 0.5), centre, zero);  // 15 reference frames
  CHECK(s.linear_velocity.y() == Approx(0.2 * std::pow(0.8, 15)));
  CHECK(s.angular_velocity.z() == Approx(0.3 * std::pow(0.8, 15)));
}

TEST_CASE("initial particles are spread about the centre in the local frame", "[motion]") {
  const float n[6] = {1, -2, 0, 0, 0, 1};
  const ParticleState s = initial_particle(start, InitialSpread{0.01, 0.1}, centre, n);
  const Eigen::Vector3d moved = s.pose.apply(centre) - start.apply(centre);
  CHECK((moved - start.rotation * Eigen::Vector3d(0.01, -0.02, 0)).norm() < 1e-12);
  CHECK(rotation_error(s.pose, start) == Approx(0.1));
  CHECK(s.linear_velocity.norm() == 0.0);
}
