// The pose refinement of the reference filter: its depth Jacobian against finite differences of the
// rasterizer, and its fit against the ground truth of scenes rendered at a known pose.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <depthtrack/error.hpp>
#include <depthtrack/tracker_config.hpp>
#include <numbers>
#include <vector>

#include "atlas/triangle_planes.hpp"
#include "model/fit_noise.hpp"
#include "reference/pose_refiner.hpp"
#include "scene.hpp"

using namespace depthtrack;
using reference::Vector6d;

namespace {
constexpr double kDegrees = 180.0 / std::numbers::pi;

const Camera kCamera = Camera::make(160, 120, 131.25, 131.25, 79.5, 59.5);

Pose object_pose() {
  return Pose({0.02, -0.01, 0.7}, Eigen::Quaterniond(Eigen::AngleAxisd(0.6, Eigen::Vector3d(1, 2, 0.5).normalized())));
}

// The fits' start: 4 mm and about 2 degrees off `truth`, turned about `centre`.
Pose start_off(const Pose& truth, const Eigen::Vector3d& centre) {
  Vector6d offset;
  offset << 0.003, -0.002, 0.0015, 0.02, -0.015, 0.02;
  return reference::apply_twist(truth, centre, offset);
}
}  // namespace

TEST_CASE("the depth Jacobian of the refinement equals finite differences of the rasterizer", "[refine]") {
  const Mesh mesh = builtin_demo_mesh();
  const Eigen::Vector3d centre = mesh.centre().cast<double>();
  const reference::Rasterizer rasterizer(mesh, kCamera, 0.05, 10.0);
  const std::vector<float> planes = render::triangle_planes(mesh);
  const size_t pixels = static_cast<size_t>(kCamera.pixel_count());
  const Pose pose = object_pose();
  std::vector<float> depth(pixels), plus(pixels), minus(pixels);
  std::vector<int> ids(pixels), ids_plus(pixels), ids_minus(pixels);
  rasterizer.render(pose, depth, ids);
  const Eigen::Matrix3d rotation = pose.rotation.toRotationMatrix();
  const Eigen::Vector3d centre_camera = pose.apply(centre);

  for (int axis = 0; axis < 6; ++axis) {
    const double step = 1e-4;  // metres or radians: float depths (6e-8 m) stay far below the change
    Vector6d twist = Vector6d::Zero();
    twist[axis] = step;
    rasterizer.render(reference::apply_twist(pose, centre, twist), plus, ids_plus);
    rasterizer.render(reference::apply_twist(pose, centre, -twist), minus, ids_minus);
    int compared = 0;
    double worst = 0;
    for (size_t k = 0; k < pixels; ++k) {
      // Interior pixels only: the same triangle in all three renderings.
      if (ids[k] < 0 || ids_plus[k] != ids[k] || ids_minus[k] != ids[k]) continue;
      const int u = static_cast<int>(k % static_cast<size_t>(kCamera.width)),
                v = static_cast<int>(k / static_cast<size_t>(kCamera.width));
      const Eigen::Vector3d ray((u - kCamera.cx) / kCamera.fx, (v - kCamera.cy) / kCamera.fy, 1.0);
      const float* plane = &planes[4 * static_cast<size_t>(ids[k])];
      const Eigen::Vector3d normal = rotation * Eigen::Vector3d(plane[0], plane[1], plane[2]);
      Vector6d row;
      if (!reference::depth_jacobian(depth[k] * ray, normal, ray, centre_camera, 0.3, row)) continue;
      const double numeric = (static_cast<double>(plus[k]) - minus[k]) / (2 * step);
      INFO("axis " << axis << ", pixel " << u << "," << v << ": analytic " << row[axis] << ", numeric " << numeric);
      REQUIRE(numeric == Approx(row[axis]).epsilon(0.01).margin(2e-3));
      worst = std::max(worst, std::abs(numeric - row[axis]));
      ++compared;
    }
    std::printf("depth Jacobian, axis %d: %d interior pixels, worst |analytic - numeric| %.2g\n", axis, compared,
                worst);
    CHECK(compared > 200);
  }
}

TEST_CASE("apply_twist and twist_between are inverses about the mesh's centre", "[refine]") {
  const Eigen::Vector3d centre(0.01, 0.02, -0.03);
  Vector6d twist;
  twist << 0.003, -0.002, 0.004, 0.02, -0.05, 0.03;
  const Pose moved = reference::apply_twist(object_pose(), centre, twist);
  CHECK((moved.apply(centre) - object_pose().apply(centre) - twist.head<3>()).norm() < 1e-12);
  CHECK((reference::twist_between(object_pose(), moved, centre) - twist).norm() < 1e-12);
}

TEST_CASE("refinement recovers the pose a noise-free scene was rendered at, also behind an occluder", "[refine]") {
  const Mesh mesh = builtin_demo_mesh();
  const Eigen::Vector3d centre = mesh.centre().cast<double>();
  const Pose truth = object_pose();
  const Pose start = start_off(truth, centre);
  TrackerConfig config;
  config.refine.iterations = 10;
  const reference::PoseRefiner refiner(mesh, kCamera, config);

  SECTION("clear view") {
    const DepthImage depth = test::render_scene(mesh, kCamera, truth);
    const reference::RefinedPose fit = refiner.refine(start, depth, {});
    std::printf("refinement, clear view: %.3g um / %.3g deg from truth after %d steps, %d pixels\n",
                1e6 * translation_error(fit.pose, truth), kDegrees * rotation_error(fit.pose, truth),
                fit.accepted_steps, fit.pixels);
    CHECK(translation_error(fit.pose, truth) < 2e-5);
    CHECK(kDegrees * rotation_error(fit.pose, truth) < 0.01);
    // The covariance is the inverse of a positive definite Hessian: finite, positive variances.
    for (int i = 0; i < 6; ++i) CHECK(fit.covariance(i, i) > 0);
    CHECK(fit.covariance.allFinite());
  }
  SECTION("a third of the object hidden 10 cm in front of it") {
    // The occluder hides the object's leftmost third; the occlusion map says 0.1 everywhere, so only
    // the residuals' responsibilities keep the occluder's pixels out of the fit.
    std::vector<float> probe(static_cast<size_t>(kCamera.pixel_count()));
    const reference::Rasterizer rasterizer(mesh, kCamera, 0.05, 10.0);
    const reference::PixelBox box = rasterizer.render(truth, probe);
    const int u1 = box.u0 + (box.u1 - box.u0) / 3;
    const DepthImage depth = test::render_scene(mesh, kCamera, truth, 1.5, box.u0, u1, truth.translation.z() - 0.1);
    const std::vector<double> occlusion(probe.size(), 0.1);
    const reference::RefinedPose fit = refiner.refine(start, depth, occlusion);
    std::printf("refinement, a third occluded: %.3g um / %.3g deg from truth after %d steps\n",
                1e6 * translation_error(fit.pose, truth), kDegrees * rotation_error(fit.pose, truth),
                fit.accepted_steps);
    CHECK(translation_error(fit.pose, truth) < 5e-5);
    CHECK(kDegrees * rotation_error(fit.pose, truth) < 0.02);
  }
}

TEST_CASE("refinement stops once the next step would move the mesh less than converged_motion", "[refine]") {
  const Mesh mesh = builtin_demo_mesh();
  const Eigen::Vector3d centre = mesh.centre().cast<double>();
  const Pose truth = object_pose();
  Vector6d offset;  // 4 mm and about 2 degrees off, on noise-free depth: Gauss-Newton converges fast
  offset << 0.003, -0.002, 0.0015, 0.02, -0.015, 0.02;
  const Pose start = reference::apply_twist(truth, centre, offset);
  const DepthImage depth = test::render_scene(mesh, kCamera, truth);
  TrackerConfig config;
  config.refine.iterations = 10;
  config.refine.fine_noise_scale = 0;  // one stage: at most 10 steps
  config.refine.converged_motion = 0;  // every step tried
  const reference::RefinedPose all = reference::PoseRefiner(mesh, kCamera, config).refine(start, depth, {});
  config.refine.converged_motion = 5e-5;
  const reference::RefinedPose stopped = reference::PoseRefiner(mesh, kCamera, config).refine(start, depth, {});
  std::printf("refinement, clear view: %d steps tried without the stopping rule, %d with it (%.3g / %.3g um off)\n",
              all.iterations, stopped.iterations, 1e6 * translation_error(all.pose, truth),
              1e6 * translation_error(stopped.pose, truth));
  CHECK(all.iterations == 10);
  CHECK(stopped.iterations >= 2);  // 4 mm needs more than one step to fall below 50 um
  CHECK(stopped.iterations < 10);
  // Stopped where the next step moves no mesh point 50 um: it is within that of where all steps end.
  const Vector6d rest = reference::twist_between(stopped.pose, all.pose, centre);
  CHECK(reference::step_motion(rest, mesh.radius()) < 5e-5);
  CHECK(translation_error(stopped.pose, truth) < 5e-5);
}

TEST_CASE("refinement parameters outside their range are named errors", "[refine]") {
  TrackerConfig config;
  config.refine.iterations = -1;
  CHECK_THROWS_WITH(config.validate(), Catch::Contains("refine iterations"));
  config = TrackerConfig{};
  config.refine.damping = std::nan("");
  CHECK_THROWS_WITH(config.validate(), Catch::Contains("refine damping"));
  config = TrackerConfig{};
  config.refine.min_incidence = 1.0;
  CHECK_THROWS_WITH(config.validate(), Catch::Contains("refine min incidence"));
  config = TrackerConfig{};
  config.refine.converged_motion = -1e-5;
  CHECK_THROWS_WITH(config.validate(), Catch::Contains("refine converged motion"));
  for (const double scale : {0.0, -0.5, std::nan(""), 10.5}) {
    config = TrackerConfig{};
    config.refine.noise_scale = scale;
    CHECK_THROWS_WITH(config.validate(), Catch::Contains("refine noise scale must be in (0, 10]"));
  }
  for (const double scale : {-0.5, std::nan(""), 10.5}) {
    config = TrackerConfig{};
    config.refine.fine_noise_scale = scale;
    CHECK_THROWS_WITH(config.validate(), Catch::Contains("refine fine noise scale must be 0"));
  }
}

TEST_CASE("a second stage of the fit at a finer noise goes on from where the first stage ends", "[refine]") {
  const Mesh mesh = builtin_demo_mesh();
  const Eigen::Vector3d centre = mesh.centre().cast<double>();
  const Pose truth = object_pose();
  const Pose start = start_off(truth, centre);
  // A flat occluder over the object's leftmost third, 2 mm in front of the nearest surface it hides:
  // its pixels lie from 2 mm to centimetres in front, and the nearer ones the filter's sigma (about
  // 3.7 mm here) still counts as the object's.
  std::vector<float> z(static_cast<size_t>(kCamera.pixel_count()));
  const reference::Rasterizer rasterizer(mesh, kCamera, 0.05, 10.0);
  const reference::PixelBox box = rasterizer.render(truth, z);
  const int u1 = box.u0 + (box.u1 - box.u0) / 3;
  float nearest = 10.0f;
  for (int v = 0; v < kCamera.height; ++v)
    for (int u = box.u0; u < u1; ++u) {
      const float d = z[static_cast<size_t>(v * kCamera.width + u)];
      if (d > 0.0f) nearest = std::min(nearest, d);
    }
  for (int v = 0; v < kCamera.height; ++v)
    for (int u = 0; u < kCamera.width; ++u) {
      float& d = z[static_cast<size_t>(v * kCamera.width + u)];
      if (u >= box.u0 && u < u1 && d > 0.0f)
        d = nearest - 0.002f;
      else if (d == 0.0f)
        d = 1.5f;
    }
  const DepthImage depth = DepthImage::from_metres(kCamera.width, kCamera.height, z);
  const std::vector<double> occlusion(z.size(), 0.1);
  TrackerConfig config;
  config.refine.iterations = 10;
  config.refine.fine_noise_scale = 0;  // the first stage alone
  const reference::RefinedPose coarse = reference::PoseRefiner(mesh, kCamera, config).refine(start, depth, occlusion);
  TrackerConfig fine_only = config;
  fine_only.refine.noise_scale = 0.5;
  const reference::PoseRefiner fine_refiner(mesh, kCamera, fine_only);
  const reference::RefinedPose fine = fine_refiner.refine(coarse.pose, depth, occlusion);
  TrackerConfig staged = config;
  staged.refine.fine_noise_scale = 0.5;
  const reference::RefinedPose both = reference::PoseRefiner(mesh, kCamera, staged).refine(start, depth, occlusion);
  std::printf(
      "refinement behind a near occluder: one stage %.3g um / %.3g deg from truth, two stages %.3g um / %.3g deg\n",
      1e6 * translation_error(coarse.pose, truth), kDegrees * rotation_error(coarse.pose, truth),
      1e6 * translation_error(both.pose, truth), kDegrees * rotation_error(both.pose, truth));
  // The two stages are the first stage's fit, then the finer fit from its pose.
  CHECK(both.pose.translation == fine.pose.translation);
  CHECK(both.pose.rotation.coeffs() == fine.pose.rotation.coeffs());
  CHECK(both.iterations == coarse.iterations + fine.iterations);
  CHECK(both.accepted_steps == coarse.accepted_steps + fine.accepted_steps);
  CHECK(both.covariance == fine.covariance);
  CHECK(both.objective == fine.objective);
  CHECK(fine.iterations > 0);
  // and the finer noise leaves the occluder's rim out: the pose ends nearer the truth.
  CHECK(translation_error(both.pose, truth) < translation_error(coarse.pose, truth));
}

TEST_CASE("the fit's own noise: sigma(y) scaled, the confidence's band and the covariance at the filter's",
          "[refine]") {
  TrackerConfig config;
  config.refine.noise_scale = 0.5;
  config.refine.fine_noise_scale = 0;  // one stage, at noise_scale
  const TrackerConfig fit = model::fit_config(config);
  CHECK(fit.observation.sigma_constant == 0.5 * config.observation.sigma_constant);
  CHECK(fit.observation.sigma_quadratic == 0.5 * config.observation.sigma_quadratic);
  CHECK(fit.loss.pixel_sigmas == 2.0 * config.loss.pixel_sigmas);  // 3 sigma of the filter: 6 of the fit
  CHECK(fit.observation.tail_weight == config.observation.tail_weight);
  // H of weights 1 / (0.5 sigma)^2 is four times the filter's: its covariance is the filter's at a quarter.
  Eigen::Matrix<double, 6, 6> h = Eigen::Matrix<double, 6, 6>::Zero();
  h.diagonal() << 4e6, 1e6, 2.5e5, 1e4, 4e4, 1e5;
  const Eigen::Matrix<double, 6, 6> c = model::fit_covariance(h, 100, 0.1, config.refine);
  CHECK(c(0, 0) == Approx(1.0 / 4e6 / 0.25));
  CHECK(c(3, 3) == Approx(1.0 / 1e4 / 0.25));
  CHECK(c(1, 2) == 0.0);
  config.refine.noise_scale = 1.0;
  CHECK(model::fit_covariance(h, 100, 0.1, config.refine)(0, 0) == Approx(1.0 / 4e6));
  // With a second stage the covariance is its H's: weights 1 / (0.35 sigma)^2.
  config.refine.fine_noise_scale = 0.35;
  CHECK(model::fit_covariance(h, 100, 0.1, config.refine)(0, 0) == Approx(1.0 / 4e6 / (0.35 * 0.35)));
}
