// --frames A:B: a range of frames out of a loaded sequence or out of any source.
#include <charconv>
#include <depthtrack/error.hpp>
#include <depthtrack/frame_source.hpp>

namespace depthtrack {

namespace {

std::optional<size_t> whole_number(const std::string& text) {
  size_t value = 0;
  const char* end = text.data() + text.size();
  const auto [stop, error] = std::from_chars(text.data(), end, value);
  if (text.empty() || error != std::errc() || stop != end) return std::nullopt;
  return value;
}

class RangeSource final : public FrameSource {
 public:
  RangeSource(std::unique_ptr<FrameSource> source, const FrameRange& range)
      : source_(std::move(source)), range_(range) {}

  const Camera& camera() const override { return source_->camera(); }
  std::optional<size_t> size() const override {
    const auto all = source_->size();
    if (!all) return range_.end ? std::optional<size_t>(*range_.end - range_.first) : std::nullopt;
    const size_t end = std::min(*all, range_.end.value_or(*all));
    return end > range_.first ? end - range_.first : 0;
  }

  std::optional<Frame> next() override {
    for (; read_ < range_.first; ++read_)
      if (!source_->next())
        throw InputError("the frame source ended after " + std::to_string(read_) + " frames, before frame " +
                         std::to_string(range_.first) + " where the range starts");
    if (range_.end && read_ >= *range_.end) return std::nullopt;
    std::optional<Frame> frame = source_->next();
    if (!frame && range_.end)
      throw InputError("the frame source ended after " + std::to_string(read_) + " frames, before frame " +
                       std::to_string(*range_.end - 1) + " where the range ends");
    if (frame) ++read_;
    return frame;
  }

 private:
  std::unique_ptr<FrameSource> source_;
  FrameRange range_;
  size_t read_ = 0;  // frames taken from source_
};

}  // namespace

FrameRange parse_frame_range(const std::string& text, const std::string& option) {
  const auto colon = text.find(':');
  const auto bad = [&](const std::string& why) {
    return InputError(option + " '" + text + "': " + why + " (A:B takes frames A to B-1, counted from 0; A: to the " +
                      "end; :B the first B)");
  };
  if (colon == std::string::npos || text.find(':', colon + 1) != std::string::npos) throw bad("is not A:B");
  const std::string first = text.substr(0, colon), end = text.substr(colon + 1);
  if (first.empty() && end.empty()) throw bad("names neither end");
  FrameRange range;
  if (!first.empty()) {
    const auto n = whole_number(first);
    if (!n) throw bad("'" + first + "' is not a whole number of frames");
    range.first = *n;
  }
  if (!end.empty()) {
    range.end = whole_number(end);
    if (!range.end) throw bad("'" + end + "' is not a whole number of frames");
    if (*range.end <= range.first) throw bad("the range is empty: B must be greater than A");
  }
  return range;
}

Sequence frames_in(const Sequence& sequence, const FrameRange& range) {
  const size_t count = sequence.frames.size();
  const size_t end = range.end.value_or(count);
  if (count == 0) throw InputError("frame range: the sequence has no frames");
  if (range.first >= count || end > count)
    throw InputError("frame range " + std::to_string(range.first) + ":" +
                     (range.end ? std::to_string(*range.end) : std::string()) + " reaches past the sequence's " +
                     std::to_string(count) + " frames (0 to " + std::to_string(count - 1) + ")");
  Sequence out = sequence;
  out.frames.assign(sequence.frames.begin() + static_cast<std::ptrdiff_t>(range.first),
                    sequence.frames.begin() + static_cast<std::ptrdiff_t>(end));
  return out;
}

std::unique_ptr<FrameSource> frames_in(std::unique_ptr<FrameSource> source, const FrameRange& range) {
  if (!source) throw InputError("frames_in: no frame source");
  return std::make_unique<RangeSource>(std::move(source), range);
}

}  // namespace depthtrack
