// The structured-light sensor model of the synthesizer, checked against the physics it imitates.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <depthtrack/synth.hpp>
#include <string>
#include <vector>

#include "reference/rasterizer.hpp"

using namespace depthtrack;

namespace {
const Camera kSmall = Camera::make(160, 120, 131.25, 131.25, 79.5, 59.5);

// A scene that is nothing but the wall at `depth`: the object is parked far outside the view.
SynthConfig wall_only(double depth) {
  SynthConfig c;
  c.camera = kSmall;
  c.frames = 4;
  c.trajectory.centre = {50.0, 0.0, 1.0};
  c.trajectory.amplitude.setZero();
  c.trajectory.rotation_amplitude.setZero();
  c.background_depth = depth;
  c.sensor.random_dropout = 0;
  c.sensor.edge_dropout = 0;
  return c;
}

std::vector<float> valid_depths(const DepthImage& image) {
  std::vector<float> out;
  for (float z : image.data())
    if (DepthImage::is_valid(z)) out.push_back(z);
  return out;
}

double standard_deviation(const std::vector<float>& values) {
  double mean = 0, square = 0;
  for (float v : values) mean += v;
  mean /= static_cast<double>(values.size());
  for (float v : values) square += (v - mean) * (v - mean);
  return std::sqrt(square / static_cast<double>(values.size()));
}
}  // namespace

TEST_CASE("without noise a plane's depth is quantized in disparity", "[synth]") {
  SynthConfig config = wall_only(1.0);
  config.sensor.disparity_noise = 0;
  const Synthesizer synth(builtin_demo_mesh(), config);
  const DepthImage depth = synth.frame(0).depth;
  const auto values = valid_depths(depth);
  REQUIRE(values.size() == static_cast<size_t>(kSmall.pixel_count()));  // no holes on a flat wall

  const double focal_baseline = kSmall.fx * config.sensor.baseline;  // 9.84375 px m
  // 1 m is 78.75 steps of 1/8 px; the nearest representable disparity is 79 steps: z = 0.99684 m.
  const double expected = focal_baseline / (79 * config.sensor.disparity_step);
  for (float z : values) {
    const double steps = focal_baseline / (z * config.sensor.disparity_step);
    REQUIRE(steps == Approx(std::round(steps)).margin(1e-3));
    REQUIRE(z == Approx(expected).epsilon(1e-6));
  }
  CHECK(std::abs(expected - 1.0) > 1e-3);  // quantization is visible, not a no-op
}

TEST_CASE("depth noise grows with the square of depth", "[synth]") {
  const Synthesizer near_wall(builtin_demo_mesh(), wall_only(1.0));
  const Synthesizer far_wall(builtin_demo_mesh(), wall_only(2.0));
  const auto at_1m = valid_depths(near_wall.frame(1).depth);
  const auto at_2m = valid_depths(far_wall.frame(1).depth);
  REQUIRE(at_1m.size() == static_cast<size_t>(kSmall.pixel_count()));
  REQUIRE(at_2m.size() == static_cast<size_t>(kSmall.pixel_count()));
  const double s1 = standard_deviation(at_1m), s2 = standard_deviation(at_2m);
  INFO("std at 1 m " << s1 << ", at 2 m " << s2);
  CHECK(s1 > 0.001);  // a 0.07 px disparity noise is millimetres at 1 m with this focal length
  CHECK(s2 / s1 > 2.5);
  CHECK(s2 / s1 < 6.0);
  // Noise and quantization do not shift the plane noticeably.
  double mean1 = 0;
  for (float z : at_1m) mean1 += z;
  CHECK(mean1 / static_cast<double>(at_1m.size()) == Approx(1.0).margin(0.01));
}

TEST_CASE("random dropout removes about the requested share of pixels", "[synth]") {
  SynthConfig config = wall_only(1.2);
  config.sensor.random_dropout = 0.2;
  const Synthesizer synth(builtin_demo_mesh(), config);
  const double missing = 1.0 - static_cast<double>(synth.frame(2).depth.valid_count()) / kSmall.pixel_count();
  CHECK(missing == Approx(0.2).margin(0.02));
}

TEST_CASE("the sensor sees nothing outside its depth range", "[synth]") {
  SynthConfig config = wall_only(5.0);  // beyond max_depth 4.5
  const Synthesizer synth(builtin_demo_mesh(), config);
  CHECK(synth.frame(0).depth.valid_count() == 0);
}

TEST_CASE("pixels at the silhouette go missing at the edge dropout rate, interior ones do not", "[synth]") {
  SynthConfig config;
  config.camera = kSmall;
  config.frames = 50;
  config.sensor.random_dropout = 0;
  config.sensor.edge_dropout = 0.6;
  const Mesh box = make_box({0.2f, 0.15f, 0.1f});
  const Synthesizer synth(box, config);
  // The object's footprint from the reference rasterizer, independently of the synthesizer.
  const reference::Rasterizer raster(box, kSmall, 0.05, 10.0);
  std::vector<float> object(static_cast<size_t>(kSmall.pixel_count()));
  auto is_object = [&](int u, int v) {
    return u >= 0 && v >= 0 && u < kSmall.width && v < kSmall.height &&
           object[static_cast<size_t>(v * kSmall.width + u)] > 0.0f;
  };
  long silhouette = 0, silhouette_missing = 0, interior = 0, interior_missing = 0;
  for (int i = 0; i < config.frames; i += 10) {
    const SynthFrame frame = synth.frame(i);
    raster.render(frame.ground_truth, object);
    for (int v = 1; v + 1 < kSmall.height; ++v)
      for (int u = 1; u + 1 < kSmall.width; ++u) {
        if (!is_object(u, v)) continue;
        const bool missing = !DepthImage::is_valid(frame.depth.at(u, v));
        if (!is_object(u - 1, v) || !is_object(u + 1, v) || !is_object(u, v - 1) || !is_object(u, v + 1)) {
          ++silhouette;
          silhouette_missing += missing;
          continue;
        }
        bool deep_inside = true;  // two pixels away from the outline
        for (int dv = -2; dv <= 2; ++dv)
          for (int du = -2; du <= 2; ++du) deep_inside = deep_inside && is_object(u + du, v + dv);
        if (!deep_inside) continue;
        ++interior;
        interior_missing += missing;
      }
  }
  REQUIRE(silhouette > 300);
  REQUIRE(interior > 1000);
  const double silhouette_rate = static_cast<double>(silhouette_missing) / silhouette;
  const double interior_rate = static_cast<double>(interior_missing) / interior;
  INFO("silhouette " << silhouette << " px, missing " << silhouette_rate << "; interior " << interior << " px, missing "
                     << interior_rate);
  CHECK(silhouette_rate == Approx(0.6).margin(0.08));
  CHECK(interior_rate < 0.02);
}

TEST_CASE("the ideal sensor reports the scene's exact z-depth, with no holes", "[synth]") {
  const Mesh mesh = builtin_demo_mesh();
  SynthConfig c;
  c.camera = kSmall;
  c.frames = 3;
  c.sensor.kind = SensorKind::Ideal;
  c.background_depth = 1.6;
  const Synthesizer scene(mesh, c);
  const SynthFrame f = scene.frame(2);
  // Independent expectation: the reference rasterizer at the ground-truth pose, the wall elsewhere.
  reference::Rasterizer r(mesh, kSmall, 0.05, 10.0);
  std::vector<float> object(static_cast<size_t>(kSmall.pixel_count()));
  r.render(f.ground_truth, object);
  int on_object = 0;
  for (size_t k = 0; k < object.size(); ++k) {
    const float expected = object[k] > 0 && object[k] < 1.6f ? object[k] : 1.6f;
    REQUIRE(f.depth.data()[k] == expected);
    on_object += object[k] > 0;
  }
  CHECK(on_object > 100);
  CHECK(sensor_kind_from_string("ideal") == SensorKind::Ideal);
  CHECK(std::string(to_string(SensorKind::StructuredLight)) == "structured-light");
  CHECK_THROWS_WITH(sensor_kind_from_string("lidar"), Catch::Contains("unknown sensor 'lidar'"));
}
