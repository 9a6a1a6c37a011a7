#pragma once
// GL's own time for a stretch of GL commands (GL_TIME_ELAPSED queries: core in GL 3.3, else
// GL_ARB_timer_query), handed out as a compute::Event so that the device filter reads it after the
// frame's one wait like its kernels' events. Where the context lacks the queries (or counts them
// with 0 bits), available() is false and why_unavailable() says so: callers time with the host clock.
#include <memory>
#include <string>

#include "atlas/gl/gl_context.hpp"
#include "compute/queue.hpp"

namespace depthtrack::render {

class GlDrawTimer {
 public:
  explicit GlDrawTimer(GlContext& context);
  ~GlDrawTimer();
  GlDrawTimer(const GlDrawTimer&) = delete;
  GlDrawTimer& operator=(const GlDrawTimer&) = delete;

  bool available() const { return state_ != nullptr; }
  const std::string& why_unavailable() const { return why_unavailable_; }

  // Brackets GL commands: begin(), the commands, end(). end() returns the event whose elapsed_ms()
  // is GL's time between the two (it waits for GL to finish them). One stretch at a time: an event
  // read after the next begin() throws BackendError rather than report the later stretch's time,
  // and so does a time longer than the host's since begin() (a broken driver timer). Let the
  // context execute a command before the first begin(): llvmpipe's first query otherwise reports
  // the time since boot.
  void begin();
  compute::EventPtr end();

  struct State;  // the query and its entry points, shared with the events

 private:
  std::shared_ptr<State> state_;
  std::string why_unavailable_;
};

}  // namespace depthtrack::render
