// The reader thread of track_sequence: frames come in order and equal to loading them directly; a
// frame that fails to load throws at its turn, naming the frame; stopping early does not hang.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <depthtrack/error.hpp>
#include <depthtrack/synth.hpp>
#include <fstream>

#include "eval/frame_reader.hpp"
#include "support.hpp"

using namespace depthtrack;

namespace {
Sequence small_sequence(const std::string& name, int frames) {
  SynthConfig c;
  c.camera = Camera::make(80, 60, 65.625, 65.625, 39.9375, 29.9375);
  c.frames = frames;
  return write_synthetic_sequence(test::temp_dir(name) / "seq", builtin_demo_mesh(), c);
}

// Pixel for pixel, missing (NaN) pixels included.
bool same_pixels(const DepthImage& a, const DepthImage& b) {
  return a.data().size() == b.data().size() &&
         std::equal(a.data().begin(), a.data().end(), b.data().begin(),
                    [](float x, float y) { return x == y || (std::isnan(x) && std::isnan(y)); });
}
}  // namespace

TEST_CASE("the frame reader delivers every frame in order, as load_depth reads it", "[io][reader]") {
  const Sequence seq = small_sequence("frame_reader_order", 5);
  FrameReader reader(seq, 2);
  for (size_t i = 0; i < seq.frames.size(); ++i) {
    INFO("frame " << i);
    CHECK(same_pixels(reader.next(), seq.load_depth(i)));
  }
  CHECK_THROWS_WITH(reader.next(), Catch::Contains("all 5 frames were already read"));
}

TEST_CASE("a frame that fails to load throws at its turn with its name, after the frames before it",
          "[io][reader][errors]") {
  const Sequence seq = small_sequence("frame_reader_error", 4);
  { std::ofstream(seq.frames[2].depth_path, std::ios::trunc) << "not a png"; }
  FrameReader reader(seq);
  CHECK(same_pixels(reader.next(), seq.load_depth(0)));
  CHECK(same_pixels(reader.next(), seq.load_depth(1)));
  try {
    reader.next();
    FAIL("frame 2 is not a PNG but was read");
  } catch (const InputError& e) {
    CHECK_THAT(e.what(), Catch::StartsWith("frame " + seq.frames[2].name + ": ") &&
                             Catch::Contains(seq.frames[2].depth_path.filename().string()));
  }
  CHECK_THROWS_WITH(reader.next(), Catch::Contains("reading stopped at the frame that failed"));
}

TEST_CASE("a frame reader left early stops its thread", "[io][reader]") {
  const Sequence seq = small_sequence("frame_reader_early", 6);
  {
    FrameReader reader(seq, 1);
    CHECK(reader.next().width() == 80);
  }  // the destructor must return although five frames were never asked for
  FrameReader unread(seq, 1);
}
