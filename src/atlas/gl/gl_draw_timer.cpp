#include "atlas/gl/gl_draw_timer.hpp"

#include <chrono>
#include <cstdio>
#include <depthtrack/error.hpp>

namespace depthtrack::render {

// The entry points are not in GlFunctions: that table is what every context must have, these are
// what a context may lack.
struct GlDrawTimer::State {
  GlContext* context = nullptr;  // null once the timer is gone (its query with it)
  GLuint query = 0;
  unsigned long long stretch = 0;               // begin() count: an event belongs to one stretch
  std::chrono::steady_clock::time_point begun;  // the host's time at begin()
  bool open = false;
  PFNGLGENQUERIESPROC GenQueries = nullptr;
  PFNGLDELETEQUERIESPROC DeleteQueries = nullptr;
  PFNGLBEGINQUERYPROC BeginQuery = nullptr;
  PFNGLENDQUERYPROC EndQuery = nullptr;
  PFNGLGETQUERYIVPROC GetQueryiv = nullptr;
  PFNGLGETQUERYOBJECTUI64VPROC GetQueryObjectui64v = nullptr;
};

namespace {

template <class F>
F entry(const GlContext& context, const char* name) {
  return reinterpret_cast<F>(context.proc_address(name));
}

// GL_VERSION starts "major.minor" on desktop GL.
bool version_at_least(const GlFunctions& gl, int major, int minor) {
  const auto* version = reinterpret_cast<const char*>(gl.GetString(GL_VERSION));
  int got_major = 0, got_minor = 0;
  if (!version || std::sscanf(version, "%d.%d", &got_major, &got_minor) != 2) return false;
  return got_major > major || (got_major == major && got_minor >= minor);
}

class GlTimerEvent final : public compute::Event {
 public:
  GlTimerEvent(std::shared_ptr<GlDrawTimer::State> state, unsigned long long stretch)
      : state_(std::move(state)), stretch_(stretch) {}

  void wait() override { elapsed_ms(); }

  // GL_QUERY_RESULT blocks until GL has executed the stretch; read once, then kept.
  double elapsed_ms() override {
    if (ms_ >= 0) return ms_;
    if (!state_->context) throw BackendError("GL draw time read after its GL context's timer was destroyed");
    if (state_->stretch != stretch_ || state_->open)
      throw BackendError("GL draw time read after the next GL draw began timing (one timed draw at a time)");
    state_->context->make_current();
    GLuint64 nanoseconds = 0;
    state_->GetQueryObjectui64v(state_->query, GL_QUERY_RESULT, &nanoseconds);
    const double gl_ms = static_cast<double>(nanoseconds) * 1e-6;
    // GL cannot have worked longer than the host has waited since begin(). llvmpipe does, on a
    // context's first query when no command preceded it: it reports the time since boot.
    const double host_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - state_->begun).count();
    if (gl_ms > 1.01 * host_ms + 0.01)
      throw BackendError("GL_TIME_ELAPSED reported " + std::to_string(gl_ms) + " ms for a draw begun " +
                         std::to_string(host_ms) + " ms ago: the GL driver's timer is wrong");
    ms_ = gl_ms;
    return ms_;
  }

 private:
  std::shared_ptr<GlDrawTimer::State> state_;
  unsigned long long stretch_;
  double ms_ = -1;
};

}  // namespace

GlDrawTimer::GlDrawTimer(GlContext& context) {
  context.make_current();
  const GlFunctions& gl = context.gl();
  if (!version_at_least(gl, 3, 3) && !context.has_extension("GL_ARB_timer_query")) {
    why_unavailable_ = "GL is older than 3.3 and lacks GL_ARB_timer_query";
    return;
  }
  auto state = std::make_shared<State>();
  state->GenQueries = entry<PFNGLGENQUERIESPROC>(context, "glGenQueries");
  state->DeleteQueries = entry<PFNGLDELETEQUERIESPROC>(context, "glDeleteQueries");
  state->BeginQuery = entry<PFNGLBEGINQUERYPROC>(context, "glBeginQuery");
  state->EndQuery = entry<PFNGLENDQUERYPROC>(context, "glEndQuery");
  state->GetQueryiv = entry<PFNGLGETQUERYIVPROC>(context, "glGetQueryiv");
  state->GetQueryObjectui64v = entry<PFNGLGETQUERYOBJECTUI64VPROC>(context, "glGetQueryObjectui64v");
  if (!state->GenQueries || !state->DeleteQueries || !state->BeginQuery || !state->EndQuery || !state->GetQueryiv ||
      !state->GetQueryObjectui64v) {
    why_unavailable_ = "GL lacks the timer query entry points (glGenQueries ... glGetQueryObjectui64v)";
    return;
  }
  // An implementation may count GL_TIME_ELAPSED with 0 bits: it has no timer.
  GLint bits = 0;
  state->GetQueryiv(GL_TIME_ELAPSED, GL_QUERY_COUNTER_BITS, &bits);
  while (gl.GetError() != GL_NO_ERROR) {
  }
  if (bits <= 0) {
    why_unavailable_ = "GL counts GL_TIME_ELAPSED with 0 bits (no GPU timer)";
    return;
  }
  state->GenQueries(1, &state->query);
  if (state->query == 0 || gl.GetError() != GL_NO_ERROR) {
    why_unavailable_ = "glGenQueries failed";
    return;
  }
  state->context = &context;
  state_ = std::move(state);
}

GlDrawTimer::~GlDrawTimer() {
  if (!state_) return;
  try {
    state_->context->make_current();
    state_->DeleteQueries(1, &state_->query);
  } catch (...) {  // the context is gone, and the query with it
  }
  state_->context = nullptr;
}

void GlDrawTimer::begin() {
  if (!state_) throw BackendError("GL timer queries are unavailable: " + why_unavailable_);
  if (state_->open) throw BackendError("GL draw timer begun twice without end()");
  state_->context->make_current();
  state_->begun = std::chrono::steady_clock::now();
  state_->BeginQuery(GL_TIME_ELAPSED, state_->query);
  ++state_->stretch;
  state_->open = true;
}

compute::EventPtr GlDrawTimer::end() {
  if (!state_ || !state_->open) throw BackendError("GL draw timer ended without begin()");
  state_->context->make_current();
  state_->EndQuery(GL_TIME_ELAPSED);
  state_->open = false;
  return std::make_shared<GlTimerEvent>(state_, state_->stretch);
}

}  // namespace depthtrack::render
