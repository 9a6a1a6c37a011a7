// The shares confidence and the search's outline test are built from, on depth images made by
// hand around the built-in object's rendered silhouette.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <depthtrack/mesh.hpp>
#include <depthtrack/tracker.hpp>

#include "reference/observation_model.hpp"
#include "reference/pose_refiner.hpp"
#include "reference/reference_filter.hpp"
#include "synth_frames.hpp"
#include "tracker/confidence_model.hpp"
#include "tracker/run_confidence.hpp"
#include "tracker/silhouette_shares.hpp"

using namespace depthtrack;

namespace {
struct Scene {
  Mesh mesh = builtin_demo_mesh();
  Camera camera = Camera::make(80, 60, 66.0, 66.0, 39.5, 29.5);
  TrackerConfig config;
  reference::Rasterizer rasterizer{mesh, camera, config.near_plane, config.observation.max_depth};
  Pose pose{Eigen::Vector3d(0, 0, 0.8), Eigen::Quaterniond::Identity()};
  std::vector<float> rendered = std::vector<float>(static_cast<size_t>(camera.pixel_count()));
  reference::PixelBox box;
  Scene() { box = rasterizer.render(pose, rendered); }

  // The object where it is drawn, `behind` elsewhere.
  std::vector<float> object_on(float behind) const {
    std::vector<float> metres(rendered.size(), behind);
    for (size_t k = 0; k < rendered.size(); ++k)
      if (rendered[k] > 0) metres[k] = rendered[k];
    return metres;
  }
  SilhouetteShares shares(const std::vector<float>& metres) {
    std::vector<float> scratch(rendered.size());
    return silhouette_shares(rasterizer, config.observation, config.loss.pixel_sigmas, pose,
                             DepthImage::from_metres(camera.width, camera.height, metres), scratch);
  }
};
}  // namespace

TEST_CASE("silhouette shares: an object before a wall stands out and an occluder's edge says nothing", "[confidence]") {
  Scene scene;
  REQUIRE(scene.box.u1 - scene.box.u0 >= 6);
  // In front of a wall 0.8 m behind it: all seen, every outline pixel sees past the edge.
  const SilhouetteShares free = scene.shares(scene.object_on(1.6f));
  CHECK(free.pixels > 20);
  CHECK(free.visible == 1.0);
  CHECK(free.separated == 1.0);
  CHECK(free.outline_nearer == 0.0);

  // A bar at 0.3 m over the right half of the box and beyond: the occluded pixels and the outline
  // pixels on the bar say nothing about the edge; the rest still sees past it.
  std::vector<float> barred = scene.object_on(1.6f);
  const int middle = (scene.box.u0 + scene.box.u1) / 2;
  for (int v = 0; v < scene.camera.height; ++v)
    for (int u = middle; u < scene.camera.width; ++u) barred[static_cast<size_t>(v * scene.camera.width + u)] = 0.3f;
  const SilhouetteShares occluded = scene.shares(barred);
  CHECK(occluded.occluded > 0.3);
  CHECK(occluded.occluded < 0.7);
  CHECK(occluded.outline_nearer > 0.2);
  CHECK(occluded.outline_nearer < 0.8);
  CHECK(occluded.separated == 1.0);

  // Pressed into a wall at its front face's depth (the surface continues past the drawn edge): no
  // outline sees past it, though the surface fits.
  float front = 10;
  for (float z : scene.rendered)
    if (z > 0) front = std::min(front, z);
  const SilhouetteShares pressed = scene.shares(scene.object_on(front));
  CHECK(pressed.visible == 1.0);
  CHECK(pressed.separated == 0.0);
  CHECK(pressed.outline_nearer == 0.0);

  // Missing depth beyond the edge (sensors drop pixels there) counts as seeing past it; a
  // silhouette with no depth measured is not confident.
  const SilhouetteShares dropped = scene.shares(scene.object_on(NAN));
  CHECK(dropped.separated == 1.0);
  const SilhouetteShares blind = scene.shares(std::vector<float>(scene.rendered.size(), NAN));
  CHECK(blind.missing == 1.0);
  CHECK(blind.visible == 0.0);
  CHECK(pose_confidence(blind) == 0.0);
}

TEST_CASE("silhouette shares: the plane's residual is the object's relief, none for a flat surface", "[confidence]") {
  Scene scene;
  // Turned to show two faces at once: its depths no longer lie on one plane.
  scene.pose.rotation = Eigen::AngleAxisd(0.8, Eigen::Vector3d(1, 1, 0).normalized());
  scene.box = scene.rasterizer.render(scene.pose, scene.rendered);
  const double sigma = reference::depth_sigma(scene.config.observation, 0.8);
  // The object itself: its pixels fit the pose exactly and no plane through them does.
  const SilhouetteShares own = scene.shares(scene.object_on(1.6f));
  INFO("own surface: plane_rms " << own.plane_rms);
  REQUIRE(own.pixels >= static_cast<int>(kPlanePixels));
  CHECK(own.visible_rms < 0.01);
  CHECK(own.plane_rms > 1.0);
  // Facing the camera (its front nearly flat, within a third of a sigma), behind a tilted plane through
  // its nearest point, 0.2 mm deeper per pixel to the right: the seen pixels lie on that plane, which
  // fits them to float rounding, better than the pose does.
  Scene facing;
  float front = 10;
  for (float z : facing.rendered)
    if (z > 0) front = std::min(front, z);
  std::vector<float> tilted(facing.rendered.size());
  for (int v = 0; v < facing.camera.height; ++v)
    for (int u = 0; u < facing.camera.width; ++u)
      tilted[static_cast<size_t>(v * facing.camera.width + u)] =
          front + 0.0002f * static_cast<float>(u - facing.box.u0);
  const SilhouetteShares flat = facing.shares(tilted);
  REQUIRE(flat.visible * flat.pixels >= static_cast<double>(kPlanePixels));
  CHECK(flat.plane_rms < 0.1e-3 / sigma);
  CHECK(flat.plane_rms < flat.visible_rms);
  // Too few pixels seen: no plane is fitted, the pose's own residual stands in.
  std::vector<float> hidden = scene.object_on(1.6f);
  int kept = 0;
  for (size_t k = 0; k < hidden.size(); ++k)
    if (scene.rendered[k] > 0 && kept++ >= 5) hidden[k] = 0.3f;  // a near occluder over all but five
  const SilhouetteShares few = scene.shares(hidden);
  CHECK(few.plane_rms == few.visible_rms);
}

// The filters with refinement report the fit's counts at the refined pose as their estimate's visible
// share: the counts must be the silhouette shares'.
TEST_CASE("the refinement's counts at a pose are the confidence's: pixels measured and within the band",
          "[confidence]") {
  Scene scene;
  std::vector<float> metres = scene.object_on(1.6f);
  // Of the covered pixels, by hand: 7 with something 0.3 m in front, 5 seen 0.2 m behind the surface,
  // 4 with no depth; the rest exactly on the surface.
  std::vector<size_t> covered;
  for (size_t k = 0; k < metres.size(); ++k)
    if (scene.rendered[k] > 0) covered.push_back(k);
  REQUIRE(covered.size() > 40);
  for (size_t i = 0; i < 16; ++i) {
    const size_t k = covered[i * 2];
    metres[k] = i < 7 ? scene.rendered[k] - 0.3f : i < 12 ? scene.rendered[k] + 0.2f : NAN;
  }
  const int measured = static_cast<int>(covered.size()) - 4, visible = measured - 12;
  const SilhouetteShares shares = scene.shares(metres);
  REQUIRE(shares.visible == Approx(static_cast<double>(visible) / measured).epsilon(1e-12));

  const reference::PoseRefiner refiner(scene.mesh, scene.camera, scene.config);
  const DepthImage depth = DepthImage::from_metres(scene.camera.width, scene.camera.height, metres);
  const reference::NormalEquations e = refiner.normal_equations(scene.pose, depth, {});
  CHECK(e.measured == measured);
  CHECK(e.visible == visible);
  CHECK(e.visible_share() == shares.visible);
  // A wider band takes the pixels 0.2 m behind in (sigma at ~0.8 m is a few millimetres).
  TrackerConfig wide = scene.config;
  wide.loss.pixel_sigmas = 0.25 / reference::depth_sigma(wide.observation, 1.0);
  CHECK(reference::PoseRefiner(scene.mesh, scene.camera, wide).normal_equations(scene.pose, depth, {}).visible ==
        visible + 5);
}

TEST_CASE(
    "a tracker reports the calibrated confidence of its estimate's silhouette shares; the filter, the fit's share",
    "[confidence]") {
  const Mesh mesh = builtin_demo_mesh();
  const SynthConfig synth = test::small_scene(12);
  const Synthesizer scene(mesh, synth);
  TrackerConfig config;
  config.particles = 100;
  config.width = synth.camera.width;
  config.height = synth.camera.height;
  config.backend = "reference";
  Tracker tracker(mesh, synth.camera, config);
  tracker.initialize(scene.ground_truth(0.0));
  const reference::Rasterizer rasterizer(mesh, synth.camera, config.near_plane, config.observation.max_depth);
  std::vector<float> scratch(static_cast<size_t>(synth.camera.pixel_count()));
  for (int i = 0; i < synth.frames; ++i) {
    const SynthFrame f = scene.frame(i);
    const Estimate e = tracker.update(f.depth, f.timestamp);
    const SilhouetteShares shares =
        silhouette_shares(rasterizer, config.observation, config.loss.pixel_sigmas, e.pose, f.depth, scratch);
    REQUIRE(shares.pixels > 20);
    REQUIRE(e.evidence.visible == shares.visible);
    REQUIRE(e.evidence.separated == shares.separated);
    REQUIRE(e.evidence.visible_rms == shares.visible_rms);
    // The run's first frame reports its own evidence; later supported ones at least that, and the run
    // raises none above 0.99 (tests/tracker/test_run_confidence.cpp).
    if (i == 0)
      REQUIRE(e.confidence == pose_confidence(shares));
    else
      REQUIRE(e.confidence >= pose_confidence(shares));
    REQUIRE(e.confidence <= std::max(pose_confidence(shares), RunConfidence::kMostConfident));
  }
  // The filter's own estimate carries the fit's visible share.
  reference::ReferenceFilter filter(mesh, synth.camera, config);
  filter.initialize(scene.ground_truth(0.0), InitialSpread{0.01, 0.05});
  for (int i = 0; i < synth.frames; ++i) {
    const SynthFrame f = scene.frame(i);
    const Estimate e = filter.update(f.depth, i == 0 ? 0.0 : f.timestamp - scene.frame(i - 1).timestamp);
    const SilhouetteShares shares =
        silhouette_shares(rasterizer, config.observation, config.loss.pixel_sigmas, e.pose, f.depth, scratch);
    REQUIRE(shares.pixels > 20);
    REQUIRE(e.confidence == shares.visible);
  }
}
