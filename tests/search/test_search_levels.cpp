// The box search's two levels (search::SearchSettings::two_level): a sparse rotation set first, then
// only the grid rotations near its best pairs. Against a score that peaks at a known pose, both ways
// find it, and the two levels score under half the poses.
#include <catch2/catch.hpp>
#include <cmath>

#include "search/global_search.hpp"
#include "search/rotation_set.hpp"

using namespace depthtrack;

namespace {
// A 20 cm cube (radius 17 cm) 60 cm in front of the built-in camera at 80x60.
search::SearchObject cube() {
  search::SearchObject o;
  for (int i = 0; i < 8; ++i) o.vertices.emplace_back((i & 1) ? 0.1 : -0.1, (i & 2) ? 0.1 : -0.1, (i & 4) ? 0.1 : -0.1);
  o.centre = Eigen::Vector3d::Zero();
  o.radius = std::sqrt(3.0) * 0.1;
  return o;
}
}  // namespace

TEST_CASE("two-level box search finds a peaked score's pose with under half the poses", "[global]") {
  const Camera camera = Camera::make(80, 60, 525.0 / 8, 525.0 / 8, 39.9, 29.9);
  const search::SearchObject object = cube();
  const Pose truth({0.02, -0.01, 0.6},
                   Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized())));
  // Points on the cube's front face (10 cm nearer than its centre), 2 cm apart.
  std::vector<Eigen::Vector3d> surface;
  for (int i = -3; i <= 3; ++i)
    for (int j = -3; j <= 3; ++j) surface.emplace_back(0.02 + 0.02 * i, -0.01 + 0.02 * j, 0.5);
  // Highest at the truth: 1 cm off costs as much as 0.1 rad.
  const search::ScoreFunction score = [&](std::span<const Pose> poses) {
    std::vector<double> s;
    for (const Pose& p : poses) {
      const double metres = (p.translation - truth.translation).norm() / 0.01;
      const double radians = rotation_error(p, truth) / 0.1;
      s.push_back(-(metres * metres + radians * radians));
    }
    return s;
  };
  search::SearchSettings settings;
  const search::GridResolution grid = search::grid_resolution(object, camera, surface, settings);
  // The grid is finer than the sparse set by far (4 px turn the far corner 0.21 rad: 2,880 rotations).
  REQUIRE(search::rotations_for_radius(grid.rotation_radius) >
          4 * search::rotations_for_radius(settings.sparse_radius));

  const search::SearchResult one = search::global_search(object, camera, surface, score, settings);
  settings.two_level = true;
  const search::SearchResult two = search::global_search(object, camera, surface, score, settings);
  REQUIRE(!one.candidates.empty());
  REQUIRE(!two.candidates.empty());
  for (const search::SearchResult* r : {&one, &two}) {
    CHECK((r->candidates.front().pose.translation - truth.translation).norm() < 0.005);
    CHECK(rotation_error(r->candidates.front().pose, truth) < 0.05);
  }
  // The sparse pass (49 points x 446 rotations) and the grid rotations near its best tenth.
  CHECK(one.coarse_poses == surface.size() * search::rotations_for_radius(grid.rotation_radius));
  CHECK(two.coarse_poses < one.coarse_poses / 2);
  CHECK(two.coarse_poses > surface.size() * search::rotations_for_radius(settings.sparse_radius));
}
