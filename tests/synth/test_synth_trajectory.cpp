// Ground truth of synthetic sequences: consistent, smooth, reproducible, and matching the images.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <depthtrack/synth.hpp>
#include <numbers>
#include <vector>

using namespace depthtrack;

namespace {
SynthConfig small_config() {
  SynthConfig c;
  c.camera = Camera::make(160, 120, 131.25, 131.25, 79.5, 59.5);
  c.frames = 40;
  return c;
}

bool same_image(const DepthImage& a, const DepthImage& b) {
  if (a.width() != b.width() || a.height() != b.height()) return false;
  for (size_t i = 0; i < a.data().size(); ++i) {
    const float x = a.data()[i], y = b.data()[i];
    if (!(x == y || (std::isnan(x) && std::isnan(y)))) return false;
  }
  return true;
}
}  // namespace

TEST_CASE("a frame carries the ground truth of its timestamp", "[synth]") {
  const Synthesizer synth(builtin_demo_mesh(), small_config());
  for (int i : {0, 1, 13, 39}) {
    const SynthFrame frame = synth.frame(i);
    CHECK(frame.timestamp == Approx(i / 30.0));
    const Pose expected = synth.ground_truth(i / 30.0);
    CHECK(translation_error(frame.ground_truth, expected) < 1e-12);
    CHECK(rotation_error(frame.ground_truth, expected) < 1e-9);
  }
}

TEST_CASE("the ground-truth motion is smooth, moving from the start, and seen obliquely", "[synth]") {
  const Synthesizer synth(builtin_demo_mesh(), SynthConfig{});
  const double degree = std::numbers::pi / 180.0;
  double largest_step = 0, largest_turn = 0, travelled = 0;
  for (int i = 0; i < 600; ++i) {  // 20 s at 30 Hz: several periods of every component
    const Pose a = synth.ground_truth(i / 30.0), b = synth.ground_truth((i + 1) / 30.0);
    largest_step = std::max(largest_step, translation_error(a, b));
    largest_turn = std::max(largest_turn, rotation_error(a, b));
    travelled += translation_error(a, b);
  }
  INFO("largest step " << largest_step << " m, largest turn " << largest_turn / degree << " deg");
  CHECK(largest_step < 0.01);
  CHECK(largest_turn < 3 * degree);
  CHECK(travelled > 0.5);  // it does move: amplitudes of 5-8 cm, many times over

  // t = 0 is no turning point: the first step is a sizeable share of the largest.
  const Pose p0 = synth.ground_truth(0.0), p1 = synth.ground_truth(1 / 30.0);
  CHECK(translation_error(p0, p1) > 0.2 * largest_step);
  CHECK(rotation_error(p0, p1) > 0.2 * largest_turn);

  // Oblique: the viewing ray (camera z in the object frame) is not along an object axis.
  const Eigen::Vector3d view = p0.rotation.conjugate() * Eigen::Vector3d::UnitZ();
  CHECK(view.cwiseAbs().maxCoeff() < 0.95);
}

TEST_CASE("the rendered object lies where the ground truth puts it", "[synth]") {
  const Mesh mesh = builtin_demo_mesh();
  const SynthConfig config = small_config();
  const Synthesizer synth(mesh, config);
  const Eigen::Vector3d centre = mesh.centre().cast<double>();
  for (int i : {0, 11, 25}) {
    const SynthFrame frame = synth.frame(i);
    const Eigen::Vector3d c = frame.ground_truth.apply(centre);
    const Eigen::Vector2d uv = config.camera.project(c);
    std::vector<float> seen;
    for (int dv = -2; dv <= 2; ++dv)
      for (int du = -2; du <= 2; ++du) {
        const float z =
            frame.depth.at(static_cast<int>(std::lround(uv.x())) + du, static_cast<int>(std::lround(uv.y())) + dv);
        if (DepthImage::is_valid(z)) seen.push_back(z);
      }
    REQUIRE(seen.size() > 10);
    std::nth_element(seen.begin(), seen.begin() + static_cast<long>(seen.size() / 2), seen.end());
    const double median = seen[seen.size() / 2];
    INFO("frame " << i << ": centre at depth " << c.z() << ", surface seen at " << median);
    // The surface in front of the centre, within the object's radius (and a sensor step).
    CHECK(median < c.z() + 0.01);
    CHECK(median > c.z() - mesh.radius() - 0.01);
  }
}

TEST_CASE("frames are reproducible from the seed, in any order", "[synth]") {
  const Mesh mesh = builtin_demo_mesh();
  const Synthesizer first(mesh, small_config());
  const DepthImage five = first.frame(5).depth;
  first.frame(2);
  CHECK(same_image(first.frame(5).depth, five));
  const Synthesizer second(mesh, small_config());
  CHECK(same_image(second.frame(5).depth, five));
  CHECK(!same_image(first.frame(6).depth, five));

  SynthConfig other_seed = small_config();
  other_seed.seed = 8;
  CHECK(!same_image(Synthesizer(mesh, other_seed).frame(5).depth, five));

  Synthesizer moved(Synthesizer(mesh, small_config()));
  CHECK(same_image(moved.frame(5).depth, five));
}
