// The box term of a box search: a pose's visible silhouette's box (search::visible_box) against the
// detector's box, and the gate that ranks the poses agreeing with it above the others. A hand-built
// scene: a 10 cm plate 1 m in front of the camera, its left part behind a nearer bar, a wall behind.
#include <catch2/catch.hpp>
#include <cmath>

#include "search/global_search.hpp"
#include "search/visible_box.hpp"

using namespace depthtrack;

namespace {
// 100 px per metre at 1 m: the plate spans pixels 35..45 (u) and 25..35 (v).
const Camera kCamera = Camera::make(80, 60, 100, 100, 40, 30);

// The plate's points in its own frame (z = 0), 4 mm apart, 10 cm square.
std::vector<Eigen::Vector3d> plate() {
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i <= 25; ++i)
    for (int j = 0; j <= 25; ++j) points.emplace_back(-0.05 + 0.004 * i, -0.05 + 0.004 * j, 0.0);
  return points;
}

// A wall at 1.5 m; the plate at 1 m; a bar at 0.7 m over pixels u 30..39, v 20..40 (the plate's left part).
DepthImage scene() {
  DepthImage depth(80, 60);
  for (int v = 0; v < 60; ++v)
    for (int u = 0; u < 80; ++u) {
      float z = 1.5f;
      if (u >= 35 && u <= 45 && v >= 25 && v <= 35) z = 1.0f;
      if (u >= 30 && u <= 39 && v >= 20 && v <= 40) z = 0.7f;
      depth.at(u, v) = z;
    }
  return depth;
}

const Pose kRight(Eigen::Vector3d(0, 0, 1.0), Eigen::Quaterniond::Identity());
// Sunk 10 cm behind the plate's surface: every pixel it covers sees something nearer.
const Pose kSunk(Eigen::Vector3d(0, 0, 1.1), Eigen::Quaterniond::Identity());
// The detector's box: the plate's visible pixels u 40..45, v 25..35 (sensor = working, decimation 1).
const InitHint kBox = InitHint::box(40, 25, 45, 35);
}  // namespace

TEST_CASE("visible box: the right pose's visible points span the detector's box, a sunk pose's none", "[search][box]") {
  const std::vector<Eigen::Vector3d> points = plate();
  const DepthImage depth = scene();
  const ObservationModel model;
  const search::ImageBox given = search::hint_box(kBox, 1);
  CHECK(given.u0 == Approx(39.5));
  CHECK(given.u1 == Approx(45.5));
  CHECK(given.v0 == Approx(24.5));
  CHECK(given.v1 == Approx(35.5));

  // Points at u below 39.5 lie behind the bar; the rest are seen: u 39.8..45 (x from -2 mm), v 25..35.
  const search::ImageBox right = search::visible_box(points, kRight, kCamera, depth, model, 3.0);
  REQUIRE(!right.empty());
  CHECK(right.u0 == Approx(39.8).margin(1e-9));
  CHECK(right.u1 == Approx(45.0).margin(1e-9));
  CHECK(right.v0 == Approx(25.0).margin(1e-9));
  CHECK(right.v1 == Approx(35.0).margin(1e-9));
  // (5.2 x 10) / (6 x 11)
  CHECK(search::box_iou(given, right) == Approx(52.0 / 66.0).epsilon(1e-9));

  const search::ImageBox sunk = search::visible_box(points, kSunk, kCamera, depth, model, 3.0);
  CHECK(sunk.empty());
  CHECK(search::box_iou(given, sunk) == 0.0);

  // Slid 3 cm right: its points at u 38..39.2 lie behind the bar, the rest see the plate or, past u 45.5,
  // the wall behind: u 39.6..48. Its box agrees less: (5.9 x 10) / (6 x 11 + 8.4 x 10 - 59).
  const Pose slid(Eigen::Vector3d(0.03, 0, 1.0), Eigen::Quaterniond::Identity());
  const search::ImageBox aside = search::visible_box(points, slid, kCamera, depth, model, 3.0);
  REQUIRE(!aside.empty());
  CHECK(aside.u0 == Approx(39.6).margin(1e-9));
  CHECK(aside.u1 == Approx(48.0).margin(1e-9));
  CHECK(search::box_iou(given, aside) == Approx(59.0 / 91.0).epsilon(1e-9));

  // A point with no depth at its pixel is not hidden.
  DepthImage holes = depth;
  for (int v = 0; v < 60; ++v)
    for (int u = 0; u < 80; ++u) holes.at(u, v) = std::nanf("");
  const search::ImageBox all = search::visible_box(points, kSunk, kCamera, holes, model, 3.0);
  CHECK(all.u0 == Approx(40 - 0.05 / 1.1 * 100));
  CHECK(all.u1 == Approx(40 + 0.05 / 1.1 * 100));
}

TEST_CASE("box gate: the visible pose outranks a sunk one the likelihood prefers; without a box nothing changes",
          "[search][box]") {
  const std::vector<Eigen::Vector3d> points = plate();
  const DepthImage depth = scene();
  const ObservationModel model;
  const search::ImageBox given = search::hint_box(kBox, 1);
  // Stand-ins for the coarse likelihood, which on ycbv-0049's bowl scored sunk poses 1,373 and the truth 401.
  const search::ScoreFunction likelihood = [](std::span<const Pose> poses) {
    std::vector<double> s;
    for (const Pose& p : poses) s.push_back(p.translation.z() > 1.05 ? 1373.0 : 401.0);
    return s;
  };
  const search::AgreementFunction agreement = [&](std::span<const Pose> poses) {
    std::vector<double> a;
    for (const Pose& p : poses)
      a.push_back(search::box_iou(given, search::visible_box(points, p, kCamera, depth, model, 3.0)));
    return a;
  };
  const std::vector<Pose> poses{kSunk, kRight};
  const std::vector<double> a = agreement(poses);
  const double floor = search::agreement_floor(a, 0.3);
  CHECK(floor == Approx(52.0 / 66.0 - 0.3));
  const std::vector<double> gated = search::gated(likelihood, agreement, floor)(poses);
  CHECK(gated[1] == 401.0);                        // agrees: its likelihood
  CHECK(gated[0] == 1373.0 - search::kDisagrees);  // disagrees: below every pose that agrees
  CHECK(gated[1] > gated[0]);
  // No agreement (a search without a box): the likelihood alone.
  CHECK(search::gated(likelihood, nullptr, floor)(poses) == likelihood(poses));
}

TEST_CASE("box gate in the grid search: the best candidate is the agreeing peak, not the higher sunk one",
          "[search][box]") {
  // The plate as a search object; surface points on the plate's measured face and on the wall.
  search::SearchObject object;
  object.vertices = plate();
  object.centre = Eigen::Vector3d::Zero();
  object.radius = std::sqrt(2.0) * 0.05;
  const DepthImage depth = scene();
  std::vector<Eigen::Vector3d> surface;
  for (int v = 20; v <= 40; v += 2)
    for (int u = 30; u <= 50; u += 2) surface.push_back(kCamera.back_project(u, v, depth.at(u, v)));
  // And where a sunk pose lies, 30 cm behind the plate (hidden by it, in front of the wall).
  const Pose deep(Eigen::Vector3d(0, 0, 1.3), Eigen::Quaterniond::Identity());
  surface.push_back(deep.translation);
  const ObservationModel model;
  const search::ImageBox given = search::hint_box(kBox, 1);
  // Two peaks: the right pose, and the sunk pose scoring higher (as the likelihood scores a pose whose
  // pixels it explains as occluded).
  const auto peak = [](const Pose& p, const Pose& at) {
    const double metres = (p.translation - at.translation).norm() / 0.01, radians = rotation_error(p, at) / 0.1;
    return -(metres * metres + radians * radians);
  };
  const search::ScoreFunction likelihood = [&](std::span<const Pose> poses) {
    std::vector<double> s;
    for (const Pose& p : poses) s.push_back(std::max(peak(p, kRight), 100.0 + peak(p, deep)));
    return s;
  };
  const search::AgreementFunction agreement = [&](std::span<const Pose> poses) {
    std::vector<double> a;
    for (const Pose& p : poses)
      a.push_back(search::box_iou(given, search::visible_box(object.vertices, p, kCamera, depth, model, 3.0)));
    return a;
  };
  search::SearchSettings settings;
  const search::SearchResult plain = search::global_search(object, kCamera, surface, likelihood, settings);
  const search::SearchResult boxed = search::global_search(object, kCamera, surface, likelihood, settings, agreement);
  REQUIRE(!plain.candidates.empty());
  REQUIRE(!boxed.candidates.empty());
  CHECK((plain.candidates.front().pose.translation - deep.translation).norm() < 0.02);  // the likelihood alone
  const Pose best = boxed.candidates.front().pose;
  CHECK((best.translation - kRight.translation).norm() < 0.02);
  CHECK(boxed.candidates.front().score > -0.5 * search::kDisagrees);
}
