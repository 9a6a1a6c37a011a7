// The kernels' by-value parameters as the host builds them (src/model/kernel_params), by hand.
#include <catch2/catch.hpp>
#include <cmath>

#include "model/fit_noise.hpp"
#include "model/kernel_params.hpp"

using namespace depthtrack;

TEST_CASE("the motion parameters carry dbot's per-frame step at 1/30 s and the real step otherwise", "[model]") {
  const MotionModel m;  // damping 0.8, 2.5 mm and 0.02 rad per frame at 30 Hz
  const dt_motion frame = model::motion_params(model::motion_step(m, 1.0 / 30), Eigen::Vector3d(0.01, -0.02, 0.03));
  CHECK(frame.keep == Approx(0.8));
  CHECK(frame.linear_std == Approx(0.0025 * 30));  // m/s, so that one frame adds 2.5 mm
  CHECK(frame.angular_std == Approx(0.02 * 30));
  CHECK(frame.dt == Approx(1.0 / 30));
  CHECK(frame.centre_x == 0.01f);
  CHECK(frame.centre_y == -0.02f);
  CHECK(frame.centre_z == 0.03f);
  // Two frames' gap: the velocity keeps 0.8^2, and the spread grows to sqrt(1 + 0.8^2) frames' worth.
  const dt_motion gap = model::motion_params(model::motion_step(m, 2.0 / 30), Eigen::Vector3d::Zero());
  CHECK(gap.keep == Approx(0.64));
  CHECK(gap.linear_std == Approx(0.0025 * 30 * std::sqrt(1 + 0.64)));
}

TEST_CASE("the observation parameters and the occlusion code come from the configuration", "[model]") {
  TrackerConfig config;  // MODEL.md's defaults
  const dt_model p = model::model_params(config);
  CHECK(p.sigma_constant == Approx(0.003));
  CHECK(p.sigma_quadratic == Approx(0.0014247));
  CHECK(p.tail_density == Approx(0.01 / 6.0));
  CHECK(p.keep == Approx(0.99));
  CHECK(p.lambda == Approx(std::log(2.0)).epsilon(1e-3));
  CHECK(p.log_c == Approx(std::log(0.6)));
  CHECK(p.p_inf == Approx(0.25));
  CHECK(model::occlusion_definition(OcclusionStorage::PerPixelTime) == "DT_OCCLUSION=0");
  CHECK(model::occlusion_definition(OcclusionStorage::GlobalTime) == "DT_OCCLUSION=1");
  CHECK(model::occlusion_definition(OcclusionStorage::Off) == "DT_OCCLUSION=2");
}

TEST_CASE("the camera parameters are the working camera with the clip range", "[model]") {
  TrackerConfig config;
  config.near_plane = 0.1;
  config.observation.max_depth = 4.0;
  const Camera camera = Camera::make(80, 60, 65.5, 66.5, 39.5, 29.5);
  const dt_camera c = model::camera_params(camera, config, true);
  CHECK(c.fx == 65.5f);
  CHECK(c.fy == 66.5f);
  CHECK(c.cx == 39.5f);
  CHECK(c.cy == 29.5f);
  CHECK(c.near == 0.1f);
  CHECK(c.far == 4.0f);
  CHECK(c.width == 80u);
  CHECK(c.height == 60u);
  CHECK(c.cull_back_faces == 1u);
  CHECK(model::camera_params(camera, config, false).cull_back_faces == 0u);
}

TEST_CASE("a float compared with the float threshold decides as a double compared with the double one", "[model]") {
  CHECK(model::float_threshold(2.0) == 2.0f);  // representable: itself
  // 0.1 is not a float: the largest float below it; the next float up already exceeds 0.1.
  const float below = model::float_threshold(0.1);
  CHECK(static_cast<double>(below) < 0.1);
  CHECK(static_cast<double>(std::nextafter(below, 1.0f)) > 0.1);
  CHECK(std::isinf(model::float_threshold(INFINITY)));
}

// The fit's stages reach the kernels as dt_refine_args: the first stage's sigma(y) through dt_model
// (model_params of the first stage), the second's (Refinement::fine_noise_scale) in the fine_ fields,
// its confidence band widened in sigmas so that it keeps its width in metres.
TEST_CASE("the refinement parameters carry one stage, or a second at fine_noise_scale's sigma(y)", "[model]") {
  TrackerConfig config;  // sigma(y) = 0.003 + 0.0014247 y^2, band 3 sigma
  config.refine.noise_scale = 0.5;
  config.refine.fine_noise_scale = 0;
  const Eigen::Vector3d centre(0.01, 0.02, 0.03);
  const std::vector<TrackerConfig> one = model::fit_stages(config);
  REQUIRE(one.size() == 1);
  const dt_refine_args a = model::refine_params(one, centre, 0.1, 100, 2.0, 0.5, 1);
  CHECK(a.stages == 1);
  CHECK(a.iterations == 8);
  CHECK(a.pixel_sigmas == Approx(3.0 / 0.5));
  CHECK(model::model_params(one.front()).sigma_constant == Approx(0.003 * 0.5));
  CHECK(model::last_noise_scale(config.refine) == 0.5);

  config.refine.fine_noise_scale = 0.35;
  const std::vector<TrackerConfig> two = model::fit_stages(config);
  REQUIRE(two.size() == 2);
  const dt_refine_args b = model::refine_params(two, centre, 0.1, 100, 2.0, 0.5, 1);
  CHECK(b.stages == 2);
  CHECK(b.pixel_sigmas == Approx(3.0 / 0.5));  // the first stage's band as before
  CHECK(model::model_params(two.front()).sigma_constant == Approx(0.003 * 0.5));
  CHECK(b.fine_sigma_constant == Approx(0.003 * 0.35));
  CHECK(b.fine_sigma_quadratic == Approx(0.0014247 * 0.35));
  CHECK(b.fine_pixel_sigmas == Approx(3.0 / 0.35));
  CHECK(model::last_noise_scale(config.refine) == 0.35);
  // Each stage keeps a step within 0.01 nats / s^2 of the best (float rounding grows as 1 / s^2).
  CHECK(b.step_tolerance == Approx(0.01 / (0.5 * 0.5)));
  CHECK(b.fine_step_tolerance == Approx(0.01 / (0.35 * 0.35)));
  // Steps, damping and stopping are the first stage's (both stages share them).
  CHECK(b.damping == Approx(1e-2));
  CHECK(b.converged_motion == Approx(5e-5));
  CHECK(b.centre_z == 0.03f);
}
