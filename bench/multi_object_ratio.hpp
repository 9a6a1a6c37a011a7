#pragma once
// Several objects against one (the target: three objects x 2,000 particles at 80x60 in one process within
// 1.5x one object's time): rows multi_object_ratio and the two medians it divides.
#include <depthtrack/tracker_config.hpp>
#include <string>

namespace depthtrack::bench {

// One object, then three on one Device (MultiTracker, mutual occlusion off and on), `particles` each at
// 80x60 with the renderer named: the median frame (MultiTracker::update, every object's estimate out) of
// each after two warm-up frames, and three / one. ycbv-0000's three objects (started 1 cm / 5 deg off, as
// the CLI's --init-perturb "0.01 5") on `frames` frames of its clip played forth and back where the data
// folder has them, else the handset (or the built-in mesh) three times at three poses on the synthetic
// sequence, `frames` long. `step_timings` as TrackerConfig's (off: the steps' sums read 0 on a compute
// backend, and the test column ends in _untimed). Prints CSV rows: also each object alone
// (object<j>_alone_ms, the first being one_object_ms), their mean (one_object_mean_ms) and three over it
// (multi_object_ratio_to_mean);
// the three objects' median again with their host steps on the calling thread alone (host_threads 1), then
// the median of each of MultiTracker::update's stages (MultiStageTimings) for one object and three:
// <one_object|three_objects>_<stage>_ms. A refinement layout other than Auto is named in the test column.
void run_multi_object_ratio(const std::string& backend, const std::string& renderer, int particles, int frames,
                            double simplify_error = 0, bool step_timings = true,
                            RefineLayout refine_layout = RefineLayout::Auto);

}  // namespace depthtrack::bench
