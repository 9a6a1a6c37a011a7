#pragma once
// track --overlay DIR: one PNG per frame, the estimate drawn over the colour image when the
// sequence has one, else over its depth in colour.
#include <depthtrack/evaluation.hpp>
#include <filesystem>
#include <string>
#include <vector>

#include "cli/staged_outputs.hpp"
#include "viz/overlay.hpp"

namespace depthtrack::cli {

// The text printed on a frame's picture: frame and time, errors when ground truth is known, and
// the filter's state.
std::vector<std::string> overlay_text(const TrackedFrame& frame, int particles);

// Creates dir (InputError naming it when that fails) and adds dir/<frame name>.png of every frame to
// outputs (refused when one is an input, such as a BOP scene's depth/ image); returns where to write them.
std::vector<std::filesystem::path> stage_overlay(const std::filesystem::path& dir, const Sequence& sequence,
                                                 StagedOutputs& outputs);

class OverlayWriter {
 public:
  // files: where frame i's picture goes (stage_overlay's answer).
  OverlayWriter(std::vector<std::filesystem::path> files, const Mesh& mesh, const Sequence& sequence);
  // Writes frame i's picture.
  void write(size_t i, const TrackedFrame& frame, int particles) const;

 private:
  std::vector<std::filesystem::path> files_;
  const Sequence& sequence_;
  viz::OverlayPainter painter_;
};

}  // namespace depthtrack::cli
