#include "peer_run.hpp"

#include <cstdio>
#include <depthtrack/error.hpp>
#include <sstream>

namespace depthtrack::peers {

std::vector<double> parse_numbers(const std::string& text, size_t n, const std::string& option) {
  std::istringstream in(text);
  std::vector<double> v;
  double x = 0;
  while (in >> x) v.push_back(x);
  if (!in.eof() || v.size() != n)
    throw InputError(option + " takes " + std::to_string(n) + " numbers, got '" + text + "'");
  return v;
}

PeerInput load_peer_input(const std::string& mesh, const std::string& sequence, const std::string& object,
                          const std::string& resolution, const std::string& init_perturb, uint64_t seed) {
  PeerInput in{Mesh::load(mesh), load_sequence(sequence, object), 1, {}, {}};
  if (in.sequence.frames.empty() || !in.sequence.frames.front().ground_truth)
    throw InputError("'" + sequence + "' has no ground truth for its first frame: the start needs it");
  int width = 0, height = 0;
  char x = 0;
  if (std::istringstream text(resolution); !(text >> width >> x >> height) || x != 'x')
    throw InputError("--resolution '" + resolution + "' is not WxH");
  in.factor = in.sequence.camera.decimation_factor_for(width, height);
  in.camera = in.sequence.camera.decimated(in.factor);
  const auto perturb = parse_numbers(init_perturb, 2, "--init-perturb");
  in.start = perturb_pose(*in.sequence.frames.front().ground_truth, in.mesh.centre().cast<double>(), perturb[0],
                          perturb[1], seed);
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
}

}  // namespace depthtrack::peers
