#pragma once
/// @file
/// Where frames come from: a recorded folder, a stream on stdin or a named pipe, or a source of your own.
/// The tracking loops (track_source, `depthtrack track`) read frames only through FrameSource.
#include <cstddef>
#include <depthtrack/camera.hpp>
#include <depthtrack/depth_image.hpp>
#include <depthtrack/pose.hpp>
#include <depthtrack/sequence.hpp>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace depthtrack {

/// One frame as a source delivers it.
struct Frame {
  std::string name;                   ///< e.g. "000001"; what the tracking CSV's `frame` column shows
  double timestamp = 0;               ///< seconds; later than the previous frame's
  DepthImage depth;                   ///< metres, NaN = no measurement; the size of the source's camera
  std::optional<Pose> ground_truth;   ///< camera_from_object of the tracked object, when the source knows it
  std::filesystem::path colour_path;  ///< a colour image registered to the depth, when the source has one on disk
};

/// A stream of depth frames from one camera, read once, in order.
class FrameSource {
 public:
  /// Closes the source (a reader thread, a file, a pipe).
  virtual ~FrameSource() = default;
  /// The intrinsics every frame's depth is taken with; known before the first frame.
  virtual const Camera& camera() const = 0;
  /// The next frame, or nullopt once the source has ended. Throws InputError naming the frame for one that
  /// cannot be read (malformed, truncated, out of order); a source that threw is not read further.
  virtual std::optional<Frame> next() = 0;
  /// How many frames the source holds, when known beforehand (a folder); nullopt for a stream.
  virtual std::optional<size_t> size() const { return std::nullopt; }
};

/// The frames of a loaded folder sequence, decoded on a thread of their own a few frames ahead of the
/// caller. The sequence is copied.
std::unique_ptr<FrameSource> sequence_source(Sequence sequence);

/// What every kind of source may be asked for when it is opened.
struct FrameSourceOptions {
  std::string object;  ///< a folder's object whose ground truth to deliver (load_sequence's `object`)
};

/// Opens a source of a kind in the form "KIND:LOCATION":
///  - `folder:DIR` (or a DIR with no known KIND: prefix): load_sequence's folders (depthtrack's own,
///    YCB-Video, BOP, ViSP's simulated sequences);
///  - `raw:PATH` or `raw:-` (stdin): the raw depth stream (raw_stream_format() states it), from a file or a
///    named pipe.
/// Throws InputError for an unknown kind (the message lists the kinds) or a location that cannot be opened.
std::unique_ptr<FrameSource> open_frame_source(const std::string& spec, const FrameSourceOptions& options = {});

/// Opens a source of one kind from its location (what follows "KIND:").
using FrameSourceOpener =
    std::function<std::unique_ptr<FrameSource>(const std::string& location, const FrameSourceOptions& options)>;

/// Adds a kind that open_frame_source (and so `depthtrack track --source KIND:...`) then opens. InputError
/// for a name that is empty, holds ':' or is taken.
void register_frame_source(const std::string& kind, const std::string& description, FrameSourceOpener opener);

/// The kinds open_frame_source knows, each with its one-line description, built-in ones first.
std::vector<std::pair<std::string, std::string>> frame_source_kinds();

/// The text of the raw depth stream format, as `depthtrack track --help` and the docs state it.
const char* raw_stream_format();

/// A range of frames, counted from 0: first up to but not including end (nullopt: to the end).
struct FrameRange {
  size_t first = 0;           ///< the first frame kept
  std::optional<size_t> end;  ///< the first frame not kept; nullopt: to the end
};

/// Parses "A:B", "A:" or ":B" (whole numbers, A < B). InputError naming `option` for anything else.
FrameRange parse_frame_range(const std::string& text, const std::string& option = "--frames");

/// The frames of range in sequence; InputError when the range reaches past the sequence's last frame.
Sequence frames_in(const Sequence& sequence, const FrameRange& range);

/// Frames of range out of any source: the first ones skipped, the source no longer read at the range's end.
/// next() throws InputError when the source ends before the range's first frame or before its end.
std::unique_ptr<FrameSource> frames_in(std::unique_ptr<FrameSource> source, const FrameRange& range);

}  // namespace depthtrack
