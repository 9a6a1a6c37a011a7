#pragma once
// track --overlay DIR: one PNG per frame, the estimate drawn over the colour image when the
// sequence has one, else over its depth in colour.
#include <depthtrack/evaluation.hpp>
#include <filesystem>
#include <string>
#include <vector>

#include "viz/overlay.hpp"

namespace depthtrack::cli {

// The text printed on a frame's picture: frame and time, errors when ground truth is known, and
// the filter's state.
std::vector<std::string> overlay_text(const TrackedFrame& frame, int particles);

class OverlayWriter {
 public:
  // Creates dir (InputError naming it when that fails).
  OverlayWriter(const std::filesystem::path& dir, const Mesh& mesh, const Sequence& sequence);
  // Writes dir/<frame name>.png for frame i of the sequence.
  void write(size_t i, const TrackedFrame& frame, int particles) const;

 private:
  std::filesystem::path dir_;
  const Sequence& sequence_;
  viz::OverlayPainter painter_;
};

}  // namespace depthtrack::cli
