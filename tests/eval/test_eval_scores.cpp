// The scores `depthtrack eval` prints, against values worked out by hand: the ADD-S AUC, a mesh's diameter,
// a case's counts, the confidence's reliability bins; and the clip pieces it reads (label boxes, objects).
#include <png.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <depthtrack/error.hpp>
#include <fstream>

#include "cli_support.hpp"
#include "eval/case_scores.hpp"
#include "eval/clip_objects.hpp"
#include "eval/label_box.hpp"

using namespace depthtrack;

TEST_CASE("adds_auc is the area under the accuracy curve over 0-100 mm", "[eval]") {
  // Accuracy curve of 5, 20, 100 and 200 mm: 0 below 5 mm, 1/4 from 5 to 20, 2/4 from 20 to 100 (100 mm and
  // 200 mm never count below 100). Area: 15 * 0.25 + 80 * 0.5 = 43.75 mm of 100: 0.4375. NaN is left out.
  CHECK(adds_auc({0.005, 0.020, 0.100, 0.200, NAN}) == Approx(0.4375));
  CHECK(adds_auc({0.0, 0.0}) == Approx(1.0));
  CHECK(adds_auc({0.150}) == Approx(0.0));
  CHECK(std::isnan(adds_auc({NAN})));
  // Another range: 10 mm over 0-20 mm is covered from 10 to 20: half.
  CHECK(adds_auc({0.010}, 0.020) == Approx(0.5));
}

TEST_CASE("mesh_diameter is exact over the hull, a bounding-box bound for a flat mesh", "[eval]") {
  const MeshDiameter box = mesh_diameter(make_box({0.1f, 0.2f, 0.3f}));
  CHECK(box.exact);
  CHECK(box.metres == Approx(std::sqrt(0.01 + 0.04 + 0.09)).epsilon(1e-6));
  // A flat triangle spans no volume: its bounding box's diagonal, sqrt(0.2^2 + 0.1^2), bounds its 0.2 m.
  Mesh flat;
  flat.vertices = {{0, 0, 0}, {0.2f, 0, 0}, {0.1f, 0.1f, 0}};
  flat.triangles = {{0, 1, 2}};
  const MeshDiameter bound = mesh_diameter(flat);
  CHECK_FALSE(bound.exact);
  CHECK(bound.metres == Approx(std::sqrt(0.05)).epsilon(1e-6));
  CHECK(adds_tolerance(0.05) == Approx(0.005));
  CHECK(adds_tolerance(0.3) == Approx(0.010));
}

namespace {
TrackedFrame frame(double adds, TrackStatus status, double confidence) {
  TrackedFrame f;
  f.adds = adds;
  f.estimate.status = status;
  f.estimate.confidence = confidence;
  return f;
}
}  // namespace

TEST_CASE("score_case counts confident-wrong, false lost frames and recovery", "[eval]") {
  const std::vector<TrackedFrame> frames = {
      frame(0.004, TrackStatus::Tracking, 0.9),  // within the 5 mm tolerance
      frame(0.030, TrackStatus::Tracking, 0.6),  // confident and wrong
      frame(0.030, TrackStatus::Tracking, 0.4),  // wrong, but says so
      frame(0.025, TrackStatus::Lost, 0.9),      // wrong, and lost
      frame(0.003, TrackStatus::Lost, 0.1),      // a false loss
      frame(NAN, TrackStatus::NoData, 0.0),      // no ground truth: not scored
      frame(0.020, TrackStatus::Tracking, 0.5),  // exactly 20 mm is not above it
      frame(0.008, TrackStatus::Tracking, 0.5),  // within 10 mm, not within the tolerance
  };
  const CaseScores s = score_case(frames, 0.005, 3);
  CHECK(s.frames == 8);
  CHECK(s.scored == 7);
  CHECK(s.mean_adds == Approx(0.120 / 7));
  // (0.96 + 0.70 + 0.70 + 0.75 + 0.97 + 0.80 + 0.92) / 7
  CHECK(s.auc == Approx(5.8 / 7));
  CHECK(s.last_adds == Approx(0.008));
  CHECK(s.tracking == 5);
  CHECK(s.lost == 2);
  CHECK(s.no_data == 1);
  CHECK(s.confident_wrong == 1);
  CHECK(s.false_lost == 1);
  // From frame 3: lost, lost, unknown, then 20 mm while tracking: not recovered. From frame 7: 8 mm.
  REQUIRE(s.recovered);
  CHECK_FALSE(*s.recovered);
  CHECK(*score_case(frames, 0.005, 7).recovered);
  CHECK_FALSE(score_case(frames, 0.005, 8).recovered);
  CHECK_FALSE(score_case(frames, 0.005).recovered);
}

TEST_CASE("reliability bins confidence in tenths and weighs the calibration error by frames", "[eval]") {
  const Reliability r =
      reliability({{0.05, true}, {0.05, false}, {0.95, true}, {1.0, true}, {0.92, false}, {0.5, true}, {NAN, true}});
  CHECK(r.frames == 6);
  CHECK(r.bins[0].frames == 2);
  CHECK(r.bins[0].mean_confidence == Approx(0.05));
  CHECK(r.bins[0].share_within == Approx(0.5));
  CHECK(r.bins[5].frames == 1);
  CHECK(r.bins[9].frames == 3);  // 1.0 falls in the last bin
  CHECK(r.bins[9].mean_confidence == Approx(2.87 / 3));
  CHECK(r.bins[9].share_within == Approx(2.0 / 3));
  CHECK(r.bins[3].frames == 0);
  CHECK(std::isnan(r.bins[3].share_within));
  // 2/6 * |0.5 - 0.05| + 3/6 * |2/3 - 0.956667| + 1/6 * |1 - 0.5| = 0.15 + 0.145 + 0.083333
  CHECK(r.ece == Approx(0.378333).epsilon(1e-5));
  CHECK(std::isnan(reliability({}).ece));
}

namespace {
void write_label_png(const std::filesystem::path& path, int width, int height, const std::vector<unsigned char>& ids) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = static_cast<png_uint_32>(width);
  image.height = static_cast<png_uint_32>(height);
  image.format = PNG_FORMAT_GRAY;
  REQUIRE(png_image_write_to_file(&image, path.c_str(), 0, ids.data(), 0, nullptr));
}
}  // namespace

TEST_CASE("label_box finds one id's pixels in a label image", "[eval]") {
  const auto dir = test::temp_dir("eval_label_box");
  std::vector<unsigned char> ids(6 * 4, 0);
  ids[2 * 6 + 1] = 7;  // (u 1, v 2)
  ids[1 * 6 + 4] = 7;  // (u 4, v 1)
  ids[3 * 6 + 5] = 2;
  write_label_png(dir / "000001-label.png", 6, 4, ids);
  const auto box = label_box(dir / "000001-label.png", 7);
  REQUIRE(box);
  CHECK(*box == std::array<int, 4>{1, 1, 4, 2});
  CHECK(*label_box(dir / "000001-label.png", 2) == std::array<int, 4>{5, 3, 5, 3});
  CHECK_FALSE(label_box(dir / "000001-label.png", 9));
  CHECK_THROWS_AS(label_box(dir / "missing.png", 7), InputError);
  CHECK_THROWS_AS(label_box(dir / "000001-label.png", 300), InputError);
  CHECK(label_image_beside(dir / "000001-depth.png") == dir / "000001-label.png");
  CHECK(label_image_beside(dir / "000002-depth.png").empty());  // no such label image
  CHECK(label_image_beside(dir / "depth.png").empty());
}

TEST_CASE("clip_objects lists a YCB-Video clip's objects with their label ids", "[eval]") {
  const auto dir = test::temp_dir("eval_clip_objects");
  {
    std::ofstream gt(dir / "gt.json");
    gt << R"({"frames": [{"objects": [{"name": "a", "cls_index": 3}, {"name": "b", "cls_index": 5}]},
                         {"objects": [{"name": "b", "cls_index": 5}, {"name": "c", "cls_index": 1}]}]})";
  }
  const auto objects = clip_objects(dir);
  REQUIRE(objects.size() == 3);
  CHECK(objects[0].name == "a");
  CHECK(objects[0].label == 3);
  CHECK(objects[1].name == "b");
  CHECK(objects[1].label == 5);
  CHECK(objects[2].name == "c");
  CHECK(objects[2].label == 1);
  {
    std::ofstream gt(dir / "gt.json");
    gt << R"({"frames": [{"objects": [{"name": "a", "cls_index": 3}]}, {"objects": [{"name": "a", "cls_index": 4}]}]})";
  }
  CHECK_THROWS_AS(clip_objects(dir), InputError);
  // depthtrack's own layout carries one object.
  const auto own = test::write_cli_sequence("eval_clip_objects_own", 2);
  CHECK(clip_objects(own / "seq").size() == 1);
  CHECK_THROWS_AS(clip_objects(dir / "absent"), InputError);
}
