#pragma once
// The raw depth stream: depth frames on stdin, a named pipe or a file, each a text line then its pixels
// (raw_stream_format() in depthtrack/frame_source.hpp states the format).
#include <cstdio>
#include <depthtrack/frame_source.hpp>
#include <memory>
#include <string>

namespace depthtrack::io {

// Reads the stream header at once (blocking until it arrives); InputError naming `label` for a malformed one.
// file is read, and closed when the source goes unless it is stdin.
std::unique_ptr<FrameSource> raw_depth_stream(std::FILE* file, const std::string& label);

// "-" is stdin; anything else a path (a regular file or a named pipe).
std::unique_ptr<FrameSource> open_raw_depth_stream(const std::string& location, const FrameSourceOptions& options);

}  // namespace depthtrack::io
