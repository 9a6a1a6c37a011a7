// The moving occluder: measured from the images against an independent rendering of the object.
#include <algorithm>
#include <catch2/catch.hpp>
#include <depthtrack/synth.hpp>
#include <vector>

#include "reference/rasterizer.hpp"

using namespace depthtrack;

namespace {
const Camera kCamera = Camera::make(320, 240, 262.5, 262.5, 159.5, 119.5);

struct Hidden {
  long object_pixels = 0, hidden_pixels = 0;
  int first_column = -1, last_column = -1;  // columns with a hidden object pixel
  bool whole_columns = true;                // every object pixel of those columns is hidden
  double fraction() const { return object_pixels ? static_cast<double>(hidden_pixels) / object_pixels : 0.0; }
};

// An object pixel is hidden when the sensor saw something clearly in front of the object's surface.
Hidden measure(const SynthFrame& frame, const std::vector<float>& object) {
  Hidden h;
  std::vector<int> hidden_in(static_cast<size_t>(kCamera.width), 0), object_in(static_cast<size_t>(kCamera.width), 0);
  for (int v = 0; v < kCamera.height; ++v)
    for (int u = 0; u < kCamera.width; ++u) {
      const float truth = object[static_cast<size_t>(v * kCamera.width + u)];
      if (truth <= 0.0f) continue;
      ++h.object_pixels;
      ++object_in[static_cast<size_t>(u)];
      const float seen = frame.depth.at(u, v);
      if (DepthImage::is_valid(seen) && seen < truth - 0.06f) {
        ++h.hidden_pixels;
        ++hidden_in[static_cast<size_t>(u)];
        if (h.first_column < 0) h.first_column = u;
        h.first_column = std::min(h.first_column, u);
        h.last_column = std::max(h.last_column, u);
      }
    }
  for (int u = h.first_column; u >= 0 && u <= h.last_column; ++u)
    h.whole_columns = h.whole_columns && hidden_in[static_cast<size_t>(u)] == object_in[static_cast<size_t>(u)];
  return h;
}

SynthConfig clean_sensor(double occluder) {
  SynthConfig c;
  c.camera = kCamera;
  c.frames = 30;
  c.occluder_fraction = occluder;
  c.sensor.disparity_noise = 0;  // every object pixel measured, so hidden ones can be counted
  c.sensor.random_dropout = 0;
  c.sensor.edge_dropout = 0;
  return c;
}
}  // namespace

TEST_CASE("the occluder hides the requested share of the object in one band of columns that moves", "[synth]") {
  const Mesh mesh = builtin_demo_mesh();
  const SynthConfig config = clean_sensor(0.3);
  const Synthesizer synth(mesh, config);
  const reference::Rasterizer raster(mesh, kCamera, 0.05, 10.0);
  std::vector<float> object(static_cast<size_t>(kCamera.pixel_count()));
  std::vector<int> first_columns;
  for (int i = 0; i < config.frames; ++i) {
    const SynthFrame frame = synth.frame(i);
    raster.render(frame.ground_truth, object);
    const Hidden h = measure(frame, object);
    INFO("frame " << i << ": hidden " << h.fraction() << ", reported " << frame.occluded_fraction);
    REQUIRE(h.object_pixels > 500);
    CHECK(h.fraction() == Approx(0.3).margin(0.05));
    CHECK(frame.occluded_fraction == Approx(h.fraction()).margin(1e-9));
    CHECK(h.whole_columns);  // a bar spanning the object's full height
    first_columns.push_back(h.first_column);
  }
  CHECK(first_columns[0] != first_columns[15]);
}

TEST_CASE("without an occluder nothing stands in front of the object", "[synth]") {
  const Mesh mesh = builtin_demo_mesh();
  const Synthesizer synth(mesh, clean_sensor(0.0));
  const reference::Rasterizer raster(mesh, kCamera, 0.05, 10.0);
  std::vector<float> object(static_cast<size_t>(kCamera.pixel_count()));
  for (int i : {0, 7, 20}) {
    const SynthFrame frame = synth.frame(i);
    raster.render(frame.ground_truth, object);
    CHECK(frame.occluded_fraction == 0.0);
    CHECK(measure(frame, object).hidden_pixels == 0);
  }
}

TEST_CASE("a large occluder fraction is honoured too", "[synth]") {
  const Mesh mesh = builtin_demo_mesh();
  const Synthesizer synth(mesh, clean_sensor(0.8));
  const reference::Rasterizer raster(mesh, kCamera, 0.05, 10.0);
  std::vector<float> object(static_cast<size_t>(kCamera.pixel_count()));
  for (int i : {3, 17}) {
    const SynthFrame frame = synth.frame(i);
    raster.render(frame.ground_truth, object);
    CHECK(measure(frame, object).fraction() == Approx(0.8).margin(0.05));
  }
}
