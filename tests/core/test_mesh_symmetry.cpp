// A mesh's axis of near rotational symmetry (symmetry_axis): found on a closed cylinder in any pose and on
// a cylinder with a small handle, not on a box or the demo object.
#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "core/mesh_symmetry.hpp"

using namespace depthtrack;

namespace {

// A closed cylinder about z through the origin: side quads and two capping fans.
Mesh cylinder(float radius, float height, int segments) {
  Mesh m;
  for (int i = 0; i < segments; ++i) {
    const double a = 2 * std::numbers::pi * i / segments;
    const float x = radius * static_cast<float>(std::cos(a)), y = radius * static_cast<float>(std::sin(a));
    m.vertices.emplace_back(x, y, -height / 2);
    m.vertices.emplace_back(x, y, height / 2);
  }
  const int bottom = static_cast<int>(m.vertices.size());
  m.vertices.emplace_back(0.f, 0.f, -height / 2);
  m.vertices.emplace_back(0.f, 0.f, height / 2);
  for (int i = 0; i < segments; ++i) {
    const int j = (i + 1) % segments;
    m.triangles.emplace_back(2 * i, 2 * j, 2 * j + 1);
    m.triangles.emplace_back(2 * i, 2 * j + 1, 2 * i + 1);
    m.triangles.emplace_back(bottom, 2 * j, 2 * i);
    m.triangles.emplace_back(bottom + 1, 2 * i + 1, 2 * j + 1);
  }
  return m;
}

void transform(Mesh& m, const Eigen::Matrix3f& r, const Eigen::Vector3f& t) {
  for (auto& v : m.vertices) v = r * v + t;
}

}  // namespace

TEST_CASE("A cylinder's axis is found in any pose", "[mesh_symmetry]") {
  Mesh m = cylinder(0.04f, 0.03f, 96);
  const Eigen::Matrix3f r = Eigen::AngleAxisf(0.7f, Eigen::Vector3f(1, 2, 0.5f).normalized()).toRotationMatrix();
  const Eigen::Vector3f t(0.1f, -0.05f, 0.3f);
  transform(m, r, t);
  const auto axis = symmetry_axis(m);
  REQUIRE(axis);
  // The axis is r's image of z through t.
  CHECK(std::abs(axis->direction.dot((r * Eigen::Vector3f::UnitZ()).cast<double>())) > 0.9999);
  const Eigen::Vector3d off = axis->point - t.cast<double>();
  CHECK((off - off.dot(axis->direction) * axis->direction).norm() < 1e-4);
  CHECK(axis->share > 0.99);
}

TEST_CASE("A cylinder with a small handle is near-symmetric about its body's axis", "[mesh_symmetry]") {
  Mesh m = cylinder(0.04f, 0.09f, 96);
  append_mesh(m, make_box({0.03f, 0.01f, 0.05f}, {0.055f, 0.f, 0.f}));  // a handle on the side: x from 0.04 to 0.07
  const auto fitted = fit_symmetry_axis(m);
  REQUIRE(fitted);
  CHECK(std::abs(fitted->direction.z()) > 0.999);
  CHECK(Eigen::Vector2d(fitted->point.x(), fitted->point.y()).norm() < 2e-3);
  // The handle is about 12 % of the area: what the turns move off the surface.
  CHECK(fitted->share < 0.95);
  CHECK(fitted->share > kSymmetricShare);
  CHECK(symmetry_axis(m));
}

TEST_CASE("A box and the demo object have no axis of symmetry", "[mesh_symmetry]") {
  const Mesh box = make_box({0.1f, 0.06f, 0.03f});
  const auto b = fit_symmetry_axis(box);
  REQUIRE(b);
  CHECK(b->share < kSymmetricShare);
  CHECK_FALSE(symmetry_axis(box));
  // A cube turned 90 degrees maps onto itself, but 10 and 30 do not.
  CHECK_FALSE(symmetry_axis(make_box({0.05f, 0.05f, 0.05f})));
  CHECK_FALSE(symmetry_axis(builtin_demo_mesh()));
}

TEST_CASE("A mesh without a triangle of area has no axis", "[mesh_symmetry]") {
  Mesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  m.triangles = {{0, 1, 2}};
  CHECK_FALSE(fit_symmetry_axis(m));
}
