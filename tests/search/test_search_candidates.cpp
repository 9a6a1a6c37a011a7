// What a start without a pose chose among: search_candidates() after Tracker::initialize_global.
#include <catch2/catch.hpp>
#include <depthtrack/search_candidates.hpp>
#include <depthtrack/synth.hpp>

using namespace depthtrack;

TEST_CASE("the global search's candidates: best first, the best on the object and supported", "[global]") {
  const Mesh mesh = builtin_demo_mesh();
  SynthConfig synth;
  synth.camera = Camera::make(160, 120, 131.25, 131.25, 79.875, 59.875);
  synth.frames = 1;
  const SynthFrame frame = Synthesizer(mesh, synth).frame(0);
  Tracker tracker(mesh, synth.camera, TrackerConfig{});
  CHECK(search_candidates(tracker).empty());  // no search yet
  const Estimate e = tracker.initialize_global(
      frame.depth, 0.0, InitHint::near_point(frame.ground_truth.apply(mesh.centre().cast<double>())));
  const std::vector<SearchCandidate> found = search_candidates(tracker);
  REQUIRE(!found.empty());
  // The filter was seeded around the best: it and the estimate lie on the object.
  CHECK(translation_error(found.front().pose, frame.ground_truth) <= 0.02);
  CHECK(translation_error(e.pose, frame.ground_truth) <= 0.02);
  CHECK(found.front().confidence >= 0.5);
  for (size_t i = 0; i < found.size(); ++i) {
    INFO("candidate " << i);
    CHECK(found[i].score <= found.front().score);
    CHECK(found[i].confidence >= 0.0);
    CHECK(found[i].confidence <= 1.0);
  }
  // A start from a pose searches nothing: the list is emptied.
  tracker.initialize(frame.ground_truth);
  CHECK(search_candidates(tracker).empty());
}
