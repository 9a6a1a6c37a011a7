// Intrinsics: decimation and impossible values.
#include <catch2/catch.hpp>
#include <depthtrack/camera.hpp>
#include <depthtrack/error.hpp>

using namespace depthtrack;

TEST_CASE("decimated intrinsics map kept pixels onto the same rays", "[camera]") {
  const Camera full = Camera::make(640, 480, 525.0, 526.0, 319.5, 239.5);
  const Camera small = full.decimated(8);
  CHECK(small.width == 80);
  CHECK(small.height == 60);
  CHECK(small.fx == Approx(65.625));
  CHECK(small.fy == Approx(65.75));
  CHECK(small.cx == Approx(39.9375));
  CHECK(small.cy == Approx(29.9375));
  // The ray through full-resolution pixel (8u', 8v') must hit pixel (u', v') of the small image.
  for (int v = 0; v < 60; v += 7)
    for (int u = 0; u < 80; u += 9) {
      const Eigen::Vector3d p = full.back_project(8.0 * u, 8.0 * v, 1.7);
      const Eigen::Vector2d q = small.project(p);
      CHECK(q.x() == Approx(u).margin(1e-9));
      CHECK(q.y() == Approx(v).margin(1e-9));
    }
  CHECK(full.decimation_factor_for(80, 60) == 8);
  CHECK(full.decimation_factor_for(640, 480) == 1);
}

TEST_CASE("impossible intrinsics and resolutions are rejected with the reason", "[camera][errors]") {
  CHECK_THROWS_WITH(Camera::make(640, 480, 0.0, 525, 319.5, 239.5), Catch::Contains("fx"));
  CHECK_THROWS_WITH(Camera::make(640, 480, 525, -1.0, 319.5, 239.5), Catch::Contains("fy"));
  CHECK_THROWS_WITH(Camera::make(0, 480, 525, 525, 319.5, 239.5), Catch::Contains("image size"));
  CHECK_THROWS_WITH(Camera::make(640, 480, 525, 525, NAN, 239.5), Catch::Contains("principal point"));
  const Camera full = Camera::make(640, 480, 525, 525, 319.5, 239.5);
  CHECK_THROWS_WITH(full.decimated(7), Catch::Contains("not divisible"));
  CHECK_THROWS_WITH(full.decimation_factor_for(100, 60), Catch::Contains("100x60"));
  CHECK_THROWS_WITH(full.decimation_factor_for(80, 120), Catch::Contains("one integer factor"));
}
