// What every peer runner (bench/peers/*_tracking.cpp) shares, so that each sees exactly what
// `depthtrack track` sees: the sequence, mesh and intrinsics loaded by depthtrack's library, the depth
// decimated to the same working resolution, the start moved from ground truth by perturb_pose with the
// same seed as `--init-perturb`, and the result written as the CSV `depthtrack track` writes with the
// "N frames in S s" line compare-peers.sh reads.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <depthtrack/evaluation.hpp>
#include <depthtrack/tracker_config.hpp>
#include <functional>
#include <string>
#include <vector>

#include "cli/parse_values.hpp"  // the command line's value parsers, for the runners' own options

namespace depthtrack::peers {

// The options every runner takes, named as `depthtrack track` names them.
struct PeerOptions {
  std::string mesh, sequence, object, out, resolution = "80x60", init_perturb = "0.01 5";
  uint64_t seed = TrackerConfig{}.seed;
};
// Adds them to app; seed_help says what the seed seeds in this runner.
void add_peer_options(CLI::App& app, PeerOptions& options, const std::string& seed_help);

// Parses the command line and runs `run`; a parse error prints CLI11's message, any other error
// "<program>: error: <what>", with exit status 1.
int run_peer_program(CLI::App& app, int argc, char** argv, const std::string& program,
                     const std::function<void()>& run);

struct PeerInput {
  Mesh mesh;
  Sequence sequence;
  int factor = 1;  // the sensor image decimated by this
  Camera camera;   // at the working resolution
  Pose start;      // ground truth of the first frame moved by exactly init_perturb
};

// Loads and checks everything a run needs; resolution "WxH", init_perturb "METRES DEGREES".
PeerInput load_peer_input(const PeerOptions& options);

// The frame's row: the estimate, and its errors where the frame has ground truth.
TrackedFrame tracked_frame(const SequenceFrame& frame, const Pose& estimate, double effective_sample_size);

// Writes the CSV and prints "N frames in S s: F frames per second" and "wrote <out>".
void write_peer_result(const std::string& out, const std::vector<TrackedFrame>& frames, double seconds);

}  // namespace depthtrack::peers
