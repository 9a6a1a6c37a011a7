// The refined pose's covariance (model::pose_covariance): the inverse of the normal equations
// where the pixels determine every axis, and the undetermined axes set apart (+infinity, no
// correlation) where they do not: checked on hand-built systems and on a box seen face-on.
#include <catch2/catch.hpp>
#include <cmath>
#include <depthtrack/tracker_config.hpp>
#include <limits>

#include "model/pose_covariance.hpp"
#include "reference/pose_refiner.hpp"
#include "scene.hpp"

using namespace depthtrack;
using reference::Matrix6d;
using reference::Vector6d;

namespace {
// H = sum of rows' outer products: the Gauss-Newton system of these Jacobian rows (unit weights).
Matrix6d system_of(const std::vector<Vector6d>& rows) {
  Matrix6d h = Matrix6d::Zero();
  for (const Vector6d& row : rows) h += row * row.transpose();
  return h;
}

// Rows spanning every axis (a varied, well-conditioned set), then made to carry the dependency asked for.
std::vector<Vector6d> varied_rows() {
  std::vector<Vector6d> rows;
  for (int k = 0; k < 40; ++k) {
    Vector6d row;
    for (int i = 0; i < 6; ++i) row[i] = std::sin(1.3 * k + 0.7 * i * i + 0.3 * i) + (k % 6 == i ? 1.5 : 0.0);
    rows.push_back(row);
  }
  return rows;
}

bool undetermined(const Matrix6d& covariance, int axis) {
  if (!std::isinf(covariance(axis, axis)) || covariance(axis, axis) < 0) return false;
  for (int j = 0; j < 6; ++j)
    if (j != axis && (covariance(axis, j) != 0 || covariance(j, axis) != 0)) return false;
  return true;
}
}  // namespace

TEST_CASE("the pose covariance is the inverse of a well-conditioned system", "[refine]") {
  Matrix6d diagonal = Matrix6d::Zero();
  diagonal.diagonal() << 4, 9, 16, 1, 25, 100;
  const Matrix6d from_diagonal = model::pose_covariance(diagonal, 100, 0.1);
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) CHECK(from_diagonal(i, j) == Approx(i == j ? 1.0 / diagonal(i, i) : 0.0).margin(1e-15));

  const Matrix6d h = system_of(varied_rows());
  const Matrix6d inverse = h.inverse();  // Eigen's LU: an independent inverse
  const Matrix6d covariance = model::pose_covariance(h, 40, 0.1);
  CHECK((covariance - inverse).cwiseAbs().maxCoeff() <= 1e-9 * inverse.cwiseAbs().maxCoeff());
}

TEST_CASE("the pose covariance sets apart an axis the others explain and keeps the rest", "[refine]") {
  std::vector<Vector6d> rows = varied_rows();
  SECTION("an axis with nothing on it: +infinity, and the others the inverse of their own block") {
    for (Vector6d& row : rows) row[5] = 0;  // a turn about a face's normal moves no depth
    const Matrix6d h = system_of(rows);
    const Matrix6d covariance = model::pose_covariance(h, 40, 0.1);
    CHECK(undetermined(covariance, 5));
    const Eigen::Matrix<double, 5, 5> block = h.topLeftCorner<5, 5>().inverse();
    CHECK((covariance.topLeftCorner<5, 5>() - block).cwiseAbs().maxCoeff() <= 1e-9 * block.cwiseAbs().maxCoeff());
  }
  SECTION("a face's sliding, proportional to its depth: the sliding is set apart, the depth kept") {
    // A face tilted 1/100 from face-on: depth changes with x a hundredth as much as with z.
    for (Vector6d& row : rows) row[0] = 0.01 * row[2];
    const Matrix6d covariance = model::pose_covariance(system_of(rows), 40, 0.1);
    CHECK(undetermined(covariance, 0));
    for (int axis = 1; axis < 6; ++axis) CHECK(std::isfinite(covariance(axis, axis)));
    CHECK(covariance(2, 2) > 0);
  }
  SECTION("an axis the others explain but for 1e-4 is set apart; but for 1e-2 it is kept") {
    // Axis 4 = axes 1 and 3 plus a share e of an independent part: 1 - R^2 is e^2 / (its norm^2).
    for (const double share : {1e-4, 1e-1}) {
      std::vector<Vector6d> mixed = rows;
      for (size_t k = 0; k < mixed.size(); ++k)
        mixed[k][4] = mixed[k][1] + mixed[k][3] + share * (k % 2 ? 1.0 : -1.0) * 3.0;
      const Matrix6d h = system_of(mixed);
      const Matrix6d covariance = model::pose_covariance(h, 40, 0.1);
      // The variance inflation of axis 4, (C^-1)_44 = (H^-1)_44 H_44, from Eigen's inverse.
      const double inflation = h.inverse()(4, 4) * h(4, 4);
      INFO("share " << share << ": inflation " << inflation);
      const int set_apart = undetermined(covariance, 1) + undetermined(covariance, 3) + undetermined(covariance, 4);
      if (inflation > 10 * model::kMaxVarianceInflation) {
        CHECK(set_apart == 1);  // one of the three: the least informative
      } else {
        REQUIRE(inflation < model::kMaxVarianceInflation / 10);
        CHECK(set_apart == 0);
        CHECK((covariance - h.inverse()).cwiseAbs().maxCoeff() <= 1e-6 * h.inverse().cwiseAbs().maxCoeff());
      }
    }
  }
  SECTION("too few pixels: NaN everywhere") {
    CHECK(model::pose_covariance(system_of(rows), 5, 0.1).array().isNaN().all());
  }
}

TEST_CASE("a box seen face-on leaves its sliding and its turn about the view undetermined", "[refine]") {
  // The box's front face square to the camera's axis, centred on it: its side faces are edge-on
  // (grazing pixels stay out of the fit), so the depth says nothing about x, y or a turn about z.
  const Mesh box = make_box(Eigen::Vector3f(0.08f, 0.06f, 0.04f));
  const Camera camera = Camera::make(160, 120, 131.25, 131.25, 79.5, 59.5);
  const Pose face_on({0, 0, 0.6}, Eigen::Quaterniond::Identity());
  TrackerConfig config;
  const reference::PoseRefiner refiner(box, camera, config);
  const reference::RefinedPose fit = refiner.refine(face_on, test::render_scene(box, camera, face_on), {});
  INFO("covariance:\n" << fit.covariance);
  REQUIRE(fit.pixels > 100);
  CHECK(undetermined(fit.covariance, 0));  // x
  CHECK(undetermined(fit.covariance, 1));  // y
  CHECK(undetermined(fit.covariance, 5));  // the turn about the view axis
  for (const int axis : {2, 3, 4}) {       // depth and the two tilts: the face's depth gradient
    CHECK(std::isfinite(fit.covariance(axis, axis)));
    CHECK(fit.covariance(axis, axis) > 0);
  }
}
