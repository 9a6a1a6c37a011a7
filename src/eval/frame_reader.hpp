#pragma once
// Reads and decodes a sequence's depth images on a thread of its own, a few frames ahead of the
// tracker, so that PNG decoding overlaps the filter's device work instead of adding to each frame.
#include <condition_variable>
#include <cstddef>
#include <depthtrack/depth_image.hpp>
#include <depthtrack/sequence.hpp>
#include <deque>
#include <exception>
#include <mutex>
#include <thread>

namespace depthtrack {

class FrameReader {
 public:
  // Starts reading frame 0 at once; at most `ahead` decoded frames wait in memory. The sequence
  // must outlive the reader.
  explicit FrameReader(const Sequence& sequence, size_t ahead = 3);
  // Stops the thread (a frame being decoded is finished first) without reading the rest.
  ~FrameReader();
  FrameReader(const FrameReader&) = delete;
  FrameReader& operator=(const FrameReader&) = delete;

  // The next frame's depth image, in order. A frame that failed to load throws here, when its turn
  // comes (the frames before it are all delivered): an InputError naming the frame, or the
  // original exception. Past the last frame: InputError.
  DepthImage next();

 private:
  struct Slot {
    DepthImage depth;
    std::exception_ptr error;
  };
  void read_all();

  const Sequence& sequence_;
  const size_t ahead_;
  size_t delivered_ = 0;
  bool failed_ = false;  // the last frame delivered was an error: the thread has stopped
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Slot> ready_;
  bool stopping_ = false;
  std::thread thread_;  // last: starts once everything it uses is constructed
};

}  // namespace depthtrack
