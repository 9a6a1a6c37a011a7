// Pictures: the bitmap font, the overlay's silhouette marks against a hand-computed box, and
// track --overlay over depth (synthetic) and over colour (YCB-Video).
#include <catch2/catch.hpp>

#include "cli_support.hpp"
#include "viz/bitmap_font.hpp"
#include "viz/overlay.hpp"

using namespace depthtrack;
using viz::OverlayMark;
using viz::Rgb;
using viz::RgbImage;

namespace {
int lit(const RgbImage& image, int x0, int y0, int x1, int y1) {
  int n = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) n += image.at(x, y) == Rgb{255, 255, 255};
  return n;
}
}  // namespace

TEST_CASE("the bitmap font draws its 5x7 glyphs at any scale", "[viz]") {
  RgbImage one(6, 7);
  viz::draw_text(one, 0, 0, "1", {255, 255, 255});
  // "1": the stem (7), the flag (1) and the foot's two extra pixels (2).
  CHECK(lit(one, 0, 0, 6, 7) == 10);
  CHECK(lit(one, 2, 0, 3, 1) == 1);  // the top row is the stem alone
  CHECK(lit(one, 0, 0, 2, 1) + lit(one, 3, 0, 6, 1) == 0);
  RgbImage dash(12, 14);
  viz::draw_text(dash, 0, 0, "-", {255, 255, 255}, 2);
  CHECK(lit(dash, 0, 6, 10, 8) == 20);  // row 3 of the glyph, doubled both ways
  CHECK(lit(dash, 0, 0, 12, 14) == 20);
  CHECK(viz::text_width("ab", 2) == 22);
  // Lower case reads as upper case.
  RgbImage a(6, 7), upper(6, 7);
  viz::draw_text(a, 0, 0, "e", {255, 255, 255});
  viz::draw_text(upper, 0, 0, "E", {255, 255, 255});
  CHECK(lit(a, 0, 0, 6, 7) == lit(upper, 0, 0, 6, 7));
}

TEST_CASE("overlay marks a box's silhouette, its outline and nothing else", "[viz]") {
  // A 10 cm cube 1 m ahead: its front face (z = 0.95) projects to u, v in 39.5 +- 50 * 0.05 / 0.95,
  // i.e. 36.87..42.13 and 26.87..32.13, so pixel centres 37..42 and 27..32 are covered.
  const Camera camera = Camera::make(80, 60, 50, 50, 39.5, 29.5);
  const viz::OverlayPainter painter(make_box({0.1f, 0.1f, 0.1f}), camera);
  const auto marks = painter.marks(Pose({0, 0, 1.0}, Eigen::Quaterniond::Identity()));
  for (int v = 0; v < 60; ++v)
    for (int u = 0; u < 80; ++u) {
      const bool covered = u >= 37 && u <= 42 && v >= 27 && v <= 32;
      const bool border = covered && (u == 37 || u == 42 || v == 27 || v == 32);
      const OverlayMark expected = border ? OverlayMark::Outline : covered ? OverlayMark::Inside : OverlayMark::None;
      INFO(u << ", " << v);
      CHECK(marks[static_cast<size_t>(v * 80 + u)] == expected);
    }
  // Two boxes, one behind the other's edge: the nearer's border over the farther is a depth edge.
  Mesh two = make_box({0.1f, 0.1f, 0.1f});
  append_mesh(two, make_box({0.3f, 0.3f, 0.02f}, {0, 0, 0.5f}));
  const auto stepped = viz::OverlayPainter(two, camera).marks(Pose({0, 0, 1.0}, Eigen::Quaterniond::Identity()));
  CHECK(stepped[static_cast<size_t>(29 * 80 + 37)] == OverlayMark::DepthEdge);
  CHECK(stepped[static_cast<size_t>(29 * 80 + 39)] == OverlayMark::Inside);
}

TEST_CASE("track --overlay draws each frame over its depth in colour", "[viz][cli]") {
  const auto dir = test::write_cli_sequence("overlay_synthetic", 3);
  const auto [status, output] = test::run_cli(
      "track --mesh " + (dir / "object.obj").string() + " --sequence " + (dir / "seq").string() + " --out " +
          (dir / "out.csv").string() + " --particles 50 --init-from-gt --overlay " + (dir / "pictures").string(),
      dir / "log.txt");
  INFO(output);
  REQUIRE(status == 0);
  const Sequence seq = load_sequence(dir / "seq");
  for (size_t i = 0; i < seq.frames.size(); ++i) {
    const auto path = dir / "pictures" / (seq.frames[i].name + ".png");
    REQUIRE(std::filesystem::exists(path));
    const RgbImage picture = RgbImage::load_png(path);
    REQUIRE(picture.width() == 160);
    REQUIRE(picture.height() == 120);
    // The bottom-right corner shows the wall: the colour-mapped depth, untouched.
    const RgbImage depth = viz::colour_mapped_depth(seq.load_depth(i));
    CHECK(picture.at(155, 115) == depth.at(155, 115));
    int outline = 0;
    for (int v = 0; v < 120; ++v)
      for (int u = 0; u < 160; ++u) outline += picture.at(u, v) == Rgb{60, 255, 60};
    CHECK(outline > 40);                      // the object's border, a few cm across at 0.8 m
    CHECK(lit(picture, 0, 0, 160, 10) > 30);  // the frame line's letters
  }
}

TEST_CASE("track --overlay draws YCB-Video frames over their colour images", "[viz][cli][data]") {
  const auto clip = test::shared_data("sequences/ycbv-0000");
  const auto mesh = test::shared_data("meshes/ycb/025_mug.obj");
  if (!clip || !mesh) return;
  const auto dir = test::temp_dir("overlay_ycbv");
  const auto [status, output] = test::run_cli(
      "track --mesh " + mesh->string() + " --sequence " + clip->string() + " --object mug --out " +
          (dir / "out.csv").string() + " --particles 50 --init-from-gt --overlay " + (dir / "pictures").string(),
      dir / "log.txt");
  INFO(output);
  REQUIRE(status == 0);
  const Sequence seq = load_sequence(*clip, "mug");
  REQUIRE(!seq.frames.back().colour_path.empty());
  const RgbImage picture = RgbImage::load_png(dir / "pictures" / (seq.frames.back().name + ".png"));
  const RgbImage colour = RgbImage::load_png(seq.frames.back().colour_path);
  REQUIRE(picture.width() == 640);
  CHECK(picture.at(600, 450) == colour.at(600, 450));     // far from the mug and the text
  CHECK(!(picture.at(410, 200) == colour.at(410, 200)));  // the mug's body, tinted
}

TEST_CASE("track --overlay into a folder that cannot be made stops before tracking", "[viz][cli][errors]") {
  const auto dir = test::write_cli_sequence("overlay_bad_folder", 2);
  std::ofstream(dir / "file") << "x";
  const auto [status, output] = test::run_cli("track --mesh " + (dir / "object.obj").string() + " --sequence " +
                                                  (dir / "seq").string() + " --out " + (dir / "out.csv").string() +
                                                  " --init-from-gt --overlay " + (dir / "file" / "pictures").string(),
                                              dir / "log.txt");
  INFO(output);
  CHECK(status == 1);
  CHECK(output.find("--overlay: cannot create the folder '" + (dir / "file" / "pictures").string() + "'") !=
        std::string::npos);
  CHECK(!std::filesystem::exists(dir / "out.csv"));
}
