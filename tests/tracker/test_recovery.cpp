// Knowing when the object is lost and finding it again: the synthetic handset vanishes (only the
// wall is seen) for 1 s and comes back elsewhere; a 90 % occluder; the lost status and recovery.
#include <catch2/catch.hpp>
#include <cstdio>
#include <depthtrack/evaluation.hpp>
#include <depthtrack/synth.hpp>
#include <depthtrack/tracker.hpp>

#include "support.hpp"
#include "synth_frames.hpp"

using namespace depthtrack;

// Sequences: 640x480 structured light, 30 Hz, decimated to the tracker's 80x60 by the tracker itself.

TEST_CASE("synthetic handset vanishes for 1 s and returns 22 cm over: lost, then found again", "[recovery]") {
  const auto path = test::shared_data("meshes/dbot/handset.obj");
  if (!path) return;
  const Mesh mesh = Mesh::load(*path);
  SynthConfig synth;
  synth.frames = 120;  // 2 s tracked, 1 s of wall only, 1 s back
  synth.hidden_from = 2.0;
  synth.hidden_until = 3.0;
  synth.reappear_offset = {0.22, 0.0, 0.0};
  const std::vector<SynthFrame> frames = test::synthesize(mesh, synth);
  const int vanish = 60, back = 90;
  REQUIRE(!frames[vanish - 1].hidden);
  REQUIRE(frames[vanish].hidden);
  REQUIRE(!frames[back].hidden);
  // While hidden only the wall (1.6 m) is seen; the path resumes shifted by the offset.
  int nearer_than_wall = 0;
  for (float z : frames[vanish + 10].depth.data()) nearer_than_wall += DepthImage::is_valid(z) && z < 1.5f;
  REQUIRE(nearer_than_wall == 0);
  const Synthesizer unshifted(mesh, SynthConfig{});
  CHECK((frames[back].ground_truth.translation - unshifted.ground_truth(frames[back].timestamp).translation -
         synth.reappear_offset)
            .norm() < 1e-12);
  const double moved = (frames[back].ground_truth.translation - frames[vanish - 1].ground_truth.translation).norm();
  REQUIRE(moved >= 0.15);

  TrackerConfig config;  // reference, 200 particles, 80x60
  // The search while lost stops at a wall-clock budget (500 ms by default), so on a loaded machine it
  // saw less of its grid and the track after the return ended 10.0-10.4 mm off at frames 113-115
  // (measured 1 December 2026 under ctest -j2 at load 10-14; 3 mm alone). A budget the whole grid fits
  // in makes the test the same everywhere: it checks what the search finds, not the machine's load.
  config.recovery.budget_ms = 60000;
  Tracker tracker(mesh, synth.camera, config);
  tracker.initialize(frames.front().ground_truth);
  std::printf("\nhandset hidden at frame %d, back at %d, %.0f mm from where it vanished\n", vanish, back, 1000 * moved);
  std::printf("  frame  status    confidence  error mm  search ms\n");
  int first_lost = -1, found = -1, confidently_wrong = 0;
  double search_ms = 0;
  const AddsMetric adds(mesh);
  for (int i = 0; i < synth.frames; ++i) {
    const Estimate e = tracker.update(frames[i].depth, frames[i].timestamp);
    const double error = translation_error(e.pose, frames[i].ground_truth);
    const bool lost = e.status == TrackStatus::Lost;
    if (i % 5 == 0 || (i >= vanish - 1 && i <= vanish + 8) || (i >= back && i <= back + 16))
      std::printf("  %5d  %-9s %10.2f %9.1f %10.1f\n", i, to_string(e.status), e.confidence, 1000 * error,
                  e.timings.search_ms);
    search_ms = std::max(search_ms, e.timings.search_ms);
    // While hidden there is nothing to be right about: any pose reported tracking then is wrong.
    const double wrong_by = frames[i].hidden ? 1.0 : adds(e.pose, frames[i].ground_truth);
    confidently_wrong += wrong_by > 0.020 && !lost && e.confidence >= 0.5;
    if (lost && first_lost < 0) first_lost = i;
    if (i < vanish) CHECK(!lost);                  // never lost while seen and tracked
    if (i >= vanish + 6 && i < back) CHECK(lost);  // lost at most 6 frames after it vanished
    if (i >= back && found < 0 && !lost && error <= 0.010) found = i;
    if (found >= 0) CHECK(error <= 0.010);  // found again, it stays found
  }
  std::printf(
      "  lost raised at frame %d (%d after vanishing); found again at frame %d (%d after return); "
      "longest search %.0f ms\n",
      first_lost, first_lost - vanish, found, found - back, search_ms);
  CHECK(confidently_wrong == 0);
  CHECK(first_lost >= vanish);
  CHECK(first_lost <= vanish + 6);
  REQUIRE(found >= 0);
  CHECK(found <= back + 15);
}

TEST_CASE("synthetic handset behind a 90% occluder: when lost is raised", "[recovery]") {
  const auto path = test::shared_data("meshes/dbot/handset.obj");
  if (!path) return;
  const Mesh mesh = Mesh::load(*path);
  SynthConfig synth;
  synth.frames = 90;
  synth.occluder_fraction = 0.9;
  const std::vector<SynthFrame> frames = test::synthesize(mesh, synth);
  TrackerConfig config;
  config.recovery.enabled = false;  // report the status only
  Tracker tracker(mesh, synth.camera, config);
  tracker.initialize(frames.front().ground_truth);
  int first_lost = -1, lost_frames = 0, confidently_wrong = 0;
  double worst = 0;
  const AddsMetric adds(mesh);
  for (int i = 0; i < synth.frames; ++i) {
    const Estimate e = tracker.update(frames[i].depth, frames[i].timestamp);
    worst = std::max(worst, translation_error(e.pose, frames[i].ground_truth));
    confidently_wrong +=
        adds(e.pose, frames[i].ground_truth) > 0.020 && e.status == TrackStatus::Tracking && e.confidence >= 0.5;
    if (e.status == TrackStatus::Lost) {
      ++lost_frames;
      if (first_lost < 0) first_lost = i;
    }
  }
  std::printf(
      "\nhandset, 90%% occluder, %d frames: lost first at frame %d, lost in %d frames, worst error %.1f mm, "
      "%d confidently wrong\n",
      synth.frames, first_lost, lost_frames, 1000 * worst, confidently_wrong);
  // With a tenth of the object in view the estimate is not trusted: lost is raised within 6 frames, and
  // no frame more than 20 mm off is reported tracking with confidence 0.5 or more: 5-10 seen pixels are
  // fewer than the 16 a pose needs to be supported (docs/confidence.md).
  CHECK(confidently_wrong == 0);
  CHECK(first_lost >= 0);
  CHECK(first_lost <= 6);
}
