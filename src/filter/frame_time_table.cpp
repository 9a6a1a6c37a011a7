#include "filter/frame_time_table.hpp"

#include <algorithm>
#include <bit>
#include <depthtrack/error.hpp>
#include <span>
#include <sstream>
#include <unordered_map>

namespace depthtrack {

static_assert(DT_TIME_RETIRE_AGE + DT_TIME_RETIRE_EVERY < DT_TIME_CYCLE,
              "a pixel must be retired before its index comes round again");

// DT_TIME_NEVER's entry is time 0 for good (no frame takes that index); the others are written per frame.
FrameTimeTable::FrameTimeTable(compute::Queue& queue) : table_(queue, DT_TIME_TABLE), mirror_(DT_TIME_TABLE, 0.0f) {
  const float zero = 0.0f;
  table_.upload(std::span<const float>(&zero, 1), DT_TIME_NEVER);
}

void FrameTimeTable::reset() {
  next_ = 0;
  frames_since_retire_ = 0;
  frames_ = 0;
}

unsigned FrameTimeTable::begin_frame(float now) {
  const unsigned index = next_;
  mirror_[index] = now;
  next_ = (next_ + 1) % DT_TIME_CYCLE;
  ++frames_since_retire_;
  ++frames_;
  return index;
}

std::vector<float> FrameTimeTable::times(const std::vector<uint16_t>& indices) const {
  std::vector<float> out(indices.size());
  std::transform(indices.begin(), indices.end(), out.begin(), [&](uint16_t i) { return mirror_[i]; });
  return out;
}

std::vector<uint16_t> FrameTimeTable::indices(const std::vector<float>& times) const {
  std::unordered_map<uint32_t, uint16_t> index_of;
  const size_t written = std::min<size_t>(frames_, DT_TIME_CYCLE);
  for (size_t back = written; back >= 1; --back) {  // the oldest first: a newer frame of equal time wins
    const unsigned i = (next_ + DT_TIME_CYCLE - static_cast<unsigned>(back)) % DT_TIME_CYCLE;
    index_of[std::bit_cast<uint32_t>(mirror_[i])] = static_cast<uint16_t>(i);
  }
  index_of.try_emplace(std::bit_cast<uint32_t>(0.0f), static_cast<uint16_t>(DT_TIME_NEVER));
  std::vector<uint16_t> out(times.size());
  for (size_t k = 0; k < times.size(); ++k) {
    const auto found = index_of.find(std::bit_cast<uint32_t>(times[k]));
    if (found == index_of.end()) {
      std::ostringstream m;
      m.precision(9);
      m << "set_state: occlusion time " << times[k] << " s (value " << k
        << ") is not the time of a frame since the start, nor 0";
      throw InputError(m.str());
    }
    out[k] = found->second;
  }
  return out;
}

}  // namespace depthtrack
