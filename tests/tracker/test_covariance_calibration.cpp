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
  // white 0.1, smooth 0.05 over 200 pixels: 1.5 * 0.1 + 0.05 * 200 / 2 = 5.15.
  const Matrix6d c = model::calibrated_covariance(fit, 0.1, 0.05, 200);
  CHECK(model::kWhiteScale == 1.5);
  CHECK(model::kSmoothPatches == 2.0);
  CHECK(c(0, 0) == Approx(5.15e-6));
  CHECK(c(0, 1) == Approx(5.15 * 2e-7));
  CHECK(c(4, 4) == Approx(5.15e-6));
  CHECK(std::isinf(c(5, 5)));
  CHECK(c(5, 0) == 0);
  // Fewer pixels than patches: the smooth part counts once.
  CHECK(model::calibrated_covariance(fit, 0.1, 0.05, 1)(0, 0) == Approx(0.2e-6));
  // A residual of exactly 0 still leaves the least variance.
  CHECK(model::calibrated_covariance(fit, 0.0, 0.0, 100)(0, 0) == Approx(model::kMinResidualVariance * 1e-6));
  CHECK(model::calibrated_covariance(Matrix6d::Constant(std::nan("")), 0.1, 0.1, 100).array().isNaN().all());
}
