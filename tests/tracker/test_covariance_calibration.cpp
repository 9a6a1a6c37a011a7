// The reported covariance's scale (model::calibrated_covariance) from the residual's white and smooth
// parts (residual_structure): both on hand-made images and matrices, with the numbers worked by hand.
#include <catch2/catch.hpp>
#include <cmath>
#include <depthtrack/depth_image.hpp>
#include <depthtrack/tracker_config.hpp>
#include <limits>
#include <vector>

#include "model/covariance_calibration.hpp"
#include "reference/observation_model.hpp"
#include "tracker/residual_structure.hpp"

using namespace depthtrack;
using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Vector6d = Eigen::Matrix<double, 6, 1>;

namespace {
// A 6x4 image: the rendering 1 m everywhere but the left column (uncovered), the depth 1 m + offset(u, v).
struct Scene {
  std::vector<float> rendered = std::vector<float>(24, 1.0f);
  DepthImage depth = DepthImage(6, 4);
  template <class F>
  explicit Scene(F offset) {
    for (int v = 0; v < 4; ++v) {
      rendered[static_cast<size_t>(v) * 6] = 0.0f;
      for (int u = 0; u < 6; ++u) depth.at(u, v) = static_cast<float>(1.0 + offset(u, v));
    }
  }
};
}  // namespace

TEST_CASE("the residual's white part is what changes from neighbour to neighbour", "[covariance]") {
  const ObservationModel model;
  const double sigma = reference::depth_sigma(model, 1.0);  // 3 mm + 1.4247 mm at 1 m
  const double d = 0.25 * sigma;                            // well inside the 3-sigma band
  SECTION("a checkerboard: every neighbour differs, the whole variance is white") {
    const Scene s([&](int u, int v) { return (u + v) % 2 ? d : -d; });
    const ResidualStructure r = residual_structure(s.rendered, model, 3.0, s.depth);
    CHECK(r.pixels == 20);  // 5 covered columns of 4
    CHECK(r.total == Approx(0.0625).epsilon(5e-3));
    // Half the mean squared neighbour difference, (2 * 0.25)^2 / 2 = 0.125, is capped at the total.
    CHECK(r.white == Approx(r.total));
    CHECK(r.smooth() == Approx(0.0).margin(1e-12));
  }
  SECTION("a constant offset: no neighbour differs, the whole variance is smooth") {
    const Scene s([&](int, int) { return d; });
    const ResidualStructure r = residual_structure(s.rendered, model, 3.0, s.depth);
    CHECK(r.total == Approx(0.0625).epsilon(5e-3));
    CHECK(r.white == Approx(0.0).margin(1e-9));
    CHECK(r.smooth() == Approx(r.total));
  }
  SECTION("columns alternating: only the horizontal pairs differ") {
    const Scene s([&](int u, int) { return u % 2 ? d : -d; });
    const ResidualStructure r = residual_structure(s.rendered, model, 3.0, s.depth);
    // 16 horizontal pairs differing by 2d and 15 vertical ones by 0: white = 16 * 0.25 / (2 * 31) = 0.0645,
    // capped at the total, 0.0625.
    CHECK(r.white == Approx(r.total));
    const Scene rows([&](int, int v) { return v % 2 ? d : -d; });
    const ResidualStructure q = residual_structure(rows.rendered, model, 3.0, rows.depth);
    // 15 vertical pairs by 2d, 16 horizontal by 0: 15 * 0.25 / 62 = 0.0605 of the 0.0625.
    CHECK(q.white == Approx(15.0 * 0.25 / 62.0).epsilon(5e-3));
    CHECK(q.smooth() == Approx(0.0625 - 15.0 * 0.25 / 62.0).margin(3e-4));
  }
  SECTION("pixels outside the band (an occluder) and without depth are left out") {
    Scene s([&](int, int) { return d; });
    s.depth.at(3, 1) = 0.5f;                                     // in front by 0.5 m: occluded
    s.depth.at(4, 2) = std::numeric_limits<float>::quiet_NaN();  // no depth
    const ResidualStructure r = residual_structure(s.rendered, model, 3.0, s.depth);
    CHECK(r.pixels == 18);
    CHECK(r.total == Approx(0.0625).epsilon(5e-3));
    CHECK(r.white == Approx(0.0).margin(1e-9));
  }
  SECTION("nothing visible") {
    const Scene s([&](int, int) { return 1.0; });  // 1 m behind: contradicted everywhere
    const ResidualStructure r = residual_structure(s.rendered, model, 3.0, s.depth);
    CHECK(r.pixels == 0);
    CHECK(r.total == 0);
  }
}

TEST_CASE("the calibrated covariance scales the fit's by the residual's white and smooth parts", "[covariance]") {
  constexpr double inf = std::numeric_limits<double>::infinity();
  Matrix6d fit = Matrix6d::Identity() * 1e-6;
  fit(0, 1) = fit(1, 0) = 2e-7;
  fit(5, 5) = inf;  // undetermined
  // white 0.1, smooth 0.05 over 200 pixels at 80 px wide: 1.0 * 0.1 + 0.05 * 200 / 1.75 = 5.8142857.
  const Matrix6d c = model::calibrated_covariance(fit, 0.1, 0.05, 200, 80);
  CHECK(model::kWhiteScale == 1.0);
  CHECK(model::kSmoothPatches == 1.75);
  CHECK(c(0, 0) == Approx(5.8142857e-6));
  CHECK(c(0, 1) == Approx(5.8142857 * 2e-7));
  CHECK(c(4, 4) == Approx(5.8142857e-6));
  CHECK(std::isinf(c(5, 5)));
  CHECK(c(5, 0) == 0);
  // At 320 px wide: times sqrt(80 / 320) = 0.5.
  CHECK(model::calibrated_covariance(fit, 0.1, 0.05, 200, 320)(0, 0) == Approx(2.9071429e-6));
  // Fewer pixels than patches: the smooth part counts once.
  CHECK(model::calibrated_covariance(fit, 0.1, 0.05, 1, 80)(0, 0) == Approx(0.15e-6));
  // A residual of exactly 0 still leaves the least variance.
  CHECK(model::calibrated_covariance(fit, 0.0, 0.0, 100, 80)(0, 0) == Approx(model::kMinResidualVariance * 1e-6));
  CHECK(model::calibrated_covariance(Matrix6d::Constant(std::nan("")), 0.1, 0.1, 100, 80).array().isNaN().all());
}

TEST_CASE("the principal point's half pixel widens the centre's x and y only", "[covariance]") {
  Matrix6d c = Matrix6d::Identity() * 1e-6;
  c(2, 2) = std::numeric_limits<double>::infinity();
  // At 0.7 m with a 700 px focal length: half a pixel is 0.5 mm sideways, 2.5e-7 m^2.
  const Matrix6d w = model::with_principal_point(c, 0.7, 700);
  CHECK(w(0, 0) == Approx(1.25e-6));
  CHECK(w(1, 1) == Approx(1.25e-6));
  CHECK(std::isinf(w(2, 2)));
  CHECK(w(3, 3) == 1e-6);
  CHECK(w(0, 1) == 0);
}

TEST_CASE("a direction left undetermined drops out of the determined block", "[covariance]") {
  constexpr double inf = std::numeric_limits<double>::infinity();
  Matrix6d c = Matrix6d::Identity() * 1e-6;
  // A turn about (0, 0.6, 0.8) through the centre: rotation only.
  Vector6d turn;
  turn << 0, 0, 0, 0, 0.6, 0.8;
  const Matrix6d u = model::with_undetermined_direction(c, turn);
  CHECK(u(4, 4) == Approx(1e-6 + model::kUndeterminedVariance * 0.36));
  CHECK(u(4, 5) == Approx(model::kUndeterminedVariance * 0.48));
  CHECK(u(0, 0) == 1e-6);
  // With axis 5 set apart, the rest of the direction (axis 4 alone) takes the whole variance.
  c(5, 5) = inf;
  const Matrix6d v = model::with_undetermined_direction(c, turn);
  CHECK(v(4, 4) == Approx(1e-6 + model::kUndeterminedVariance));
  CHECK(std::isinf(v(5, 5)));
  CHECK(v(4, 5) == 0);
  // A direction almost all in the set-apart axis: nothing to add.
  Vector6d along;
  along << 0, 0, 0, 0, 0.01, 1;
  CHECK(model::with_undetermined_direction(c, along) == c);
  const Matrix6d none = model::undetermined_covariance();
  for (int i = 0; i < 6; ++i) CHECK(std::isinf(none(i, i)));
  CHECK(none(0, 1) == 0);
}
