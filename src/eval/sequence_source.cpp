// A loaded folder sequence as a FrameSource: its depth decoded a few frames ahead by a FrameReader.
#include <depthtrack/frame_source.hpp>

#include "eval/frame_reader.hpp"

namespace depthtrack {

namespace {

class SequenceSource final : public FrameSource {
 public:
  explicit SequenceSource(Sequence sequence) : sequence_(std::move(sequence)), reader_(sequence_) {}

  const Camera& camera() const override { return sequence_.camera; }
  std::optional<size_t> size() const override { return sequence_.frames.size(); }

  std::optional<Frame> next() override {
    if (next_ >= sequence_.frames.size()) return std::nullopt;
    const SequenceFrame& f = sequence_.frames[next_];
    Frame frame{f.name, f.timestamp, reader_.next(), f.ground_truth, f.colour_path};
    ++next_;
    return frame;
  }

 private:
  const Sequence sequence_;
  FrameReader reader_;  // after sequence_, which it reads
  size_t next_ = 0;
};

}  // namespace

std::unique_ptr<FrameSource> sequence_source(Sequence sequence) {
  return std::make_unique<SequenceSource>(std::move(sequence));
}

}  // namespace depthtrack
