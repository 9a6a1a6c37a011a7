#pragma once
// The frame times behind per-pixel-time occlusion's 16-bit indices (cl/dt_time_index.h): the device's
// table, which the weigh kernel writes one entry of per frame, and its mirror on the host, which turns
// indices back into times and times into indices for the state's download and upload (tests).
#include <cstdint>
#include <vector>

#include "compute/buffer.hpp"
#include "dt_time_index.h"

namespace depthtrack {

class FrameTimeTable {
 public:
  explicit FrameTimeTable(compute::Queue& queue);

  // After initialize: no frame yet, every pixel at DT_TIME_NEVER (time 0). The device table is left
  // as it is: an entry is read only by pixels of its frame, after weigh wrote it.
  void reset();
  // This frame's index, its time recorded in the mirror (weigh writes it on the device).
  unsigned begin_frame(float now);
  // Whether this frame must retire old indices before it weighs (every DT_TIME_RETIRE_EVERY frames).
  bool retire_due() const { return frames_since_retire_ >= DT_TIME_RETIRE_EVERY; }
  void retired() { frames_since_retire_ = 0; }

  std::vector<float> times(const std::vector<uint16_t>& indices) const;
  // InputError naming a time that is no frame's since the reset (nor 0, the start).
  std::vector<uint16_t> indices(const std::vector<float>& times) const;

  compute::Buffer<float>& device() { return table_; }

 private:
  compute::Buffer<float> table_;
  std::vector<float> mirror_;
  unsigned next_ = 0, frames_since_retire_ = 0;
  size_t frames_ = 0;  // since the reset, for which entries hold a frame's time
};

}  // namespace depthtrack
