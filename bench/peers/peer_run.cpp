#include "peer_run.hpp"

#include <cstdio>
#include <iostream>
#include <depthtrack/error.hpp>

namespace depthtrack::peers {

void add_peer_options(CLI::App& app, PeerOptions& o, const std::string& seed_help) {
  app.add_option("--mesh", o.mesh, "Object mesh (metres)")->required();
  app.add_option("--sequence", o.sequence, "Sequence folder (depthtrack layout or YCB-Video clip)")->required();
  app.add_option("--object", o.object, "Object of a multi-object clip");
  app.add_option("--out", o.out, "CSV to write (the columns of `depthtrack track`)")->required();
  app.add_option("--resolution", o.resolution, "Working resolution WxH (the sensor image decimated)")
      ->capture_default_str();
  app.add_option("--seed", o.seed, seed_help)->capture_default_str();
  app.add_option("--init-perturb", o.init_perturb, "Start from ground truth moved by exactly \"METRES DEGREES\"")
      ->capture_default_str();
}

int run_peer_program(CLI::App& app, int argc, char** argv, const std::string& program,
                     const std::function<void()>& run) {
  try {
    app.parse(argc, argv);
    run();
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    std::cerr << program << ": error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

PeerInput load_peer_input(const PeerOptions& o) {
  PeerInput in{Mesh::load(o.mesh), load_sequence(o.sequence, o.object), 1, {}, {}};
  if (in.sequence.frames.empty() || !in.sequence.frames.front().ground_truth)
    throw InputError("'" + o.sequence + "' has no ground truth for its first frame: the start needs it");
  const auto [width, height] = cli::parse_resolution(o.resolution);
  in.factor = in.sequence.camera.decimation_factor_for(width, height);
  in.camera = in.sequence.camera.decimated(in.factor);
  const auto perturb = cli::parse_numbers(o.init_perturb, 2, "--init-perturb");
  in.start = perturb_pose(*in.sequence.frames.front().ground_truth, in.mesh.centre().cast<double>(), perturb[0],
                          perturb[1], o.seed);
  return in;
}

TrackedFrame tracked_frame(const SequenceFrame& frame, const Pose& estimate, double effective_sample_size) {
  TrackedFrame f;
  f.name = frame.name;
  f.timestamp = frame.timestamp;
  f.estimate.pose = estimate;
  f.estimate.effective_sample_size = effective_sample_size;
  f.ground_truth = frame.ground_truth;
  if (f.ground_truth) {
    f.translation_error = translation_error(estimate, *f.ground_truth);
    f.rotation_error = rotation_error(estimate, *f.ground_truth);
  }
  return f;
}

void write_peer_result(const std::string& out, const std::vector<TrackedFrame>& frames, double seconds) {
  write_tracking_csv(out, frames);
  std::printf("%zu frames in %.2f s: %.1f frames per second\n", frames.size(), seconds,
              static_cast<double>(frames.size()) / seconds);
  std::printf("wrote %s\n", out.c_str());
}

}  // namespace depthtrack::peers
