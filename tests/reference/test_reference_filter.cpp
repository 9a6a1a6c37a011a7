// The reference filter's per-frame computation against independent statements of it.
#include <catch2/catch.hpp>
#include <depthtrack/error.hpp>
#include <depthtrack/tracker.hpp>

#include "reference/observation_model.hpp"
#include "reference/reference_filter.hpp"
#include "scene.hpp"

using namespace depthtrack;
using namespace depthtrack::reference;

namespace {
const Camera camera = Camera::make(80, 60, 65.625, 65.625, 39.9375, 29.9375);
const Pose truth({0.0, 0.0, 0.8}, Eigen::Quaterniond(Eigen::AngleAxisd(0.6, Eigen::Vector3d(1, 1, 0).normalized())));

// Without the pose refinement unless asked: these tests state the particle filter's own steps.
TrackerConfig small_config(OcclusionStorage mode, int particles = 50, bool refine = false) {
  TrackerConfig c;
  c.particles = particles;
  c.occlusion_storage = mode;
  c.seed = 11;
  c.refine.enabled = refine;
  return c;
}
}  // namespace

TEST_CASE("without occlusion a particle's log-likelihood is the sum of log(p_vis / p_bg) over covered valid pixels",
          "[filter]") {
  const Mesh mesh = builtin_demo_mesh();
  DepthImage depth = test::render_scene(mesh, camera, truth);
  // Knock out some object pixels: they must contribute nothing.
  for (int u = 30; u < 50; ++u) depth.at(u, 30) = NAN;
  ReferenceFilter filter(mesh, camera, small_config(OcclusionStorage::Off, 1));
  filter.initialize(truth, InitialSpread{0, 0});
  filter.update(depth, 0.0);

  reference::Rasterizer r(mesh, camera, 0.05, 6.0);
  std::vector<float> rendered(static_cast<size_t>(camera.pixel_count()));
  r.render(truth, rendered);
  double expected = 0;
  int used = 0;
  for (size_t k = 0; k < rendered.size(); ++k) {
    const float y = depth.data()[k];
    if (rendered[k] <= 0 || !DepthImage::is_valid(y)) continue;
    const PixelDensities d = pixel_densities(ObservationModel{}, y, rendered[k]);
    expected += std::log(d.visible / d.background);
    ++used;
  }
  CHECK(used > 50);
  CHECK(filter.last_log_likelihoods()[0] == Approx(expected).epsilon(1e-12));
  // Every used pixel sees the object exactly: about +5.8 each at 0.8 m.
  CHECK(expected / used > 5.0);
}

TEST_CASE("per-pixel-time and global-time storage give the same likelihoods over irregular frames", "[filter]") {
  const Mesh mesh = builtin_demo_mesh();
  ReferenceFilter per_pixel(mesh, camera, small_config(OcclusionStorage::PerPixelTime));
  ReferenceFilter global(mesh, camera, small_config(OcclusionStorage::GlobalTime));
  per_pixel.initialize(truth, InitialSpread{0.01, 0.05});
  global.initialize(truth, InitialSpread{0.01, 0.05});
  const double steps[] = {0.0, 1.0 / 30, 0.1, 0.02, 1.0 / 30, 0.25, 1.0 / 30, 1.0 / 30};
  int frame = 0;
  for (double dt : steps) {
    // An occluder sweeping over the object, so occlusion states differ per pixel and over time.
    const int band = 25 + 3 * frame++;
    const DepthImage depth = test::render_scene(mesh, camera, truth, 1.5, band, band + 8);
    per_pixel.update(depth, dt);
    global.update(depth, dt);
    for (size_t i = 0; i < per_pixel.last_log_likelihoods().size(); ++i)
      REQUIRE(per_pixel.last_log_likelihoods()[i] == Approx(global.last_log_likelihoods()[i]).epsilon(1e-5));
    REQUIRE(per_pixel.last_parents() == global.last_parents());
  }
}

TEST_CASE("occlusion modelling explains an occluder that the plain model punishes", "[filter]") {
  const Mesh mesh = builtin_demo_mesh();
  // The occluder hides a band across the object's middle, 30 cm in front.
  const DepthImage depth = test::render_scene(mesh, camera, truth, 1.5, 34, 46, 0.5);
  ReferenceFilter with(mesh, camera, small_config(OcclusionStorage::PerPixelTime, 1));
  ReferenceFilter without(mesh, camera, small_config(OcclusionStorage::Off, 1));
  with.initialize(truth, InitialSpread{0, 0});
  without.initialize(truth, InitialSpread{0, 0});
  with.update(depth, 0.0);
  without.update(depth, 0.0);
  // Each occluded pixel: log((0.9 p_vis + 0.1 p_occ) / p_bg) against log(p_vis / p_bg), with p_vis
  // only the outlier tail there; so the occlusion-aware likelihood is far higher.
  CHECK(with.last_log_likelihoods()[0] > without.last_log_likelihoods()[0] + 20.0);
}

TEST_CASE("the filter resamples a degenerate cloud and children copy their parents", "[filter]") {
  const Mesh mesh = builtin_demo_mesh();
  ReferenceFilter filter(mesh, camera, small_config(OcclusionStorage::PerPixelTime, 40));
  filter.initialize(truth, InitialSpread{0.03, 0.2});  // wide: most particles are poor
  const DepthImage depth = test::render_scene(mesh, camera, truth);
  const auto before = filter.particles();
  const Estimate e = filter.update(depth, 0.0);
  REQUIRE(e.resampled);
  CHECK(e.effective_sample_size < 10.0);
  const auto& parents = filter.last_parents();
  for (size_t child = 0; child < parents.size(); ++child) {
    const auto& parent = before[static_cast<size_t>(parents[child])];
    CHECK(translation_error(filter.particles()[child].pose, parent.pose) == 0.0);
  }
  // Parents are chosen in order by systematic resampling, favouring the best particle.
  CHECK(std::is_sorted(parents.begin(), parents.end()));
  const auto& ll = filter.last_log_likelihoods();
  const int best = static_cast<int>(std::max_element(ll.begin(), ll.end()) - ll.begin());
  CHECK(std::count(parents.begin(), parents.end(), best) >= 2);
}

TEST_CASE("with refinement every particle moves by the one twist that puts the heaviest on the refined pose",
          "[filter][refine]") {
  const Mesh mesh = builtin_demo_mesh();
  const Eigen::Vector3d centre = mesh.centre().cast<double>();
  ReferenceFilter plain(mesh, camera, small_config(OcclusionStorage::PerPixelTime, 40));
  ReferenceFilter refined(mesh, camera, small_config(OcclusionStorage::PerPixelTime, 40, true));
  plain.initialize(truth, InitialSpread{0.01, 0.05});
  refined.initialize(truth, InitialSpread{0.01, 0.05});
  const DepthImage depth = test::render_scene(mesh, camera, truth);
  const Estimate before = plain.update(depth, 0.0);  // the same frame without the refinement
  const Estimate after = refined.update(depth, 0.0);
  // The refined pose is nearer the truth the scene was rendered at, and has a covariance.
  CHECK(translation_error(after.pose, truth) < 0.2 * translation_error(before.pose, truth));
  CHECK(translation_error(after.pose, truth) < 1e-4);
  CHECK(after.covariance.allFinite());
  CHECK(std::isnan(before.covariance(0, 0)));
  REQUIRE(plain.last_parents() == refined.last_parents());
  const Vector6d correction = twist_between(plain.particles()[0].pose, refined.particles()[0].pose, centre);
  CHECK(correction.head<3>().norm() > 1e-5);  // the refinement did move the cloud
  int on_refined_pose = 0;
  for (size_t i = 0; i < plain.particles().size(); ++i) {
    const Vector6d moved = twist_between(plain.particles()[i].pose, refined.particles()[i].pose, centre);
    CHECK((moved - correction).norm() < 1e-9);
    on_refined_pose += translation_error(refined.particles()[i].pose, after.pose) < 1e-12 &&
                       rotation_error(refined.particles()[i].pose, after.pose) < 1e-9;
  }
  // The heaviest particle's children sit exactly on the refined pose.
  CHECK(on_refined_pose >= 1);
}
