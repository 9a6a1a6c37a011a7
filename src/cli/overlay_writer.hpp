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

// Several objects' text: the frame and time, then per object its name with its errors and state.
std::vector<std::string> overlay_text(const std::vector<const TrackedFrame*>& frames,
                                      const std::vector<std::string>& names, int particles);

class OverlayWriter {
 public:
  // files: where frame i's picture goes (stage_overlay's answer); meshes: the objects drawn, one or several.
  OverlayWriter(std::vector<std::filesystem::path> files, const std::vector<const Mesh*>& meshes,
                const Sequence& sequence);
  // Writes frame i's picture with each object's estimate (frames[j] of meshes[j]); names label the text
  // lines when there are several.
  void write(size_t i, const std::vector<const TrackedFrame*>& frames, const std::vector<std::string>& names,
             int particles) const;
  void write(size_t i, const TrackedFrame& frame, int particles) const { write(i, {&frame}, {""}, particles); }

 private:
  std::vector<std::filesystem::path> files_;
  const Sequence& sequence_;
  std::vector<viz::OverlayPainter> painters_;
};

}  // namespace depthtrack::cli
