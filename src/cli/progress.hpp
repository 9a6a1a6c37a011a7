#pragma once
// Progress on a terminal: a one-line bar for counted work (frames, bench cases), and a ticking line for a
// step that cannot be counted (preparing a model, the global search) once it has run a second. Drawn only
// when the stream is a terminal, so that redirected output carries no trace of them.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <string>
#include <thread>

namespace depthtrack::cli {

struct ProgressOutput {
  std::FILE* stream = stderr;
  bool terminal = isatty(2) != 0;     // draw at all
  std::chrono::milliseconds delay{};  // drawn once the step has run this long
};

class ProgressBar {
 public:
  ProgressBar(std::string label, int total, ProgressOutput out = {})
      : label_(std::move(label)), total_(total), out_(out), start_(std::chrono::steady_clock::now()) {}
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;
  ~ProgressBar() { finish(); }

  void update(int done, const std::string& suffix = "") {
    done_ = done;
    suffix_ = suffix;
    if (out_.terminal && total_ > 0 && std::chrono::steady_clock::now() - start_ >= out_.delay) draw();
  }
  // A line of its own on the stream whether or not it is a terminal; above the bar when one is drawn.
  void note(const std::string& line) {
    const bool redraw = drawn_;
    if (drawn_) std::fprintf(out_.stream, "\r\033[K");
    std::fprintf(out_.stream, "%s\n", line.c_str());
    drawn_ = false;
    if (redraw) draw();
    std::fflush(out_.stream);
  }
  void finish() {
    if (drawn_) std::fprintf(out_.stream, "\n");
    drawn_ = false;
  }

 private:
  void draw() {
    const int width = 30, filled = std::min(done_, total_) * width / total_;
    std::fprintf(out_.stream, "\r%s [%s%s] %d/%d %s\033[K", label_.c_str(),
                 std::string(static_cast<size_t>(filled), '#').c_str(),
                 std::string(static_cast<size_t>(width - filled), ' ').c_str(), done_, total_, suffix_.c_str());
    std::fflush(out_.stream);
    drawn_ = true;
  }

  std::string label_, suffix_;
  int total_, done_ = 0;
  ProgressOutput out_;
  std::chrono::steady_clock::time_point start_;
  bool drawn_ = false;
};

// While it lives: "LABEL... N s", redrawn each second from the first on; once over, "LABEL: T s" stays.
class ProgressWait {
 public:
  explicit ProgressWait(std::string label, ProgressOutput out = {.delay = std::chrono::seconds(1)})
      : label_(std::move(label)), out_(out) {
    if (out_.terminal) ticker_ = std::thread([this] { tick(); });
  }
  ProgressWait(const ProgressWait&) = delete;
  ProgressWait& operator=(const ProgressWait&) = delete;
  ~ProgressWait() {
    if (!ticker_.joinable()) return;
    {
      std::lock_guard lock(mutex_);
      over_ = true;
    }
    wake_.notify_all();
    ticker_.join();
    if (drawn_)
      std::fprintf(out_.stream, "\r%s: %.1f s\033[K\n", label_.c_str(),
                   std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count());
    std::fflush(out_.stream);
  }

 private:
  void tick() {
    std::unique_lock lock(mutex_);
    auto next = start_ + out_.delay;
    while (!wake_.wait_until(lock, next, [this] { return over_; })) {
      const auto seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
      std::fprintf(out_.stream, "\r%s... %.0f s\033[K", label_.c_str(), seconds);
      std::fflush(out_.stream);
      drawn_ = true;
      next += std::chrono::seconds(1);
    }
  }

  std::string label_;
  ProgressOutput out_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  std::mutex mutex_;
  std::condition_variable wake_;
  bool over_ = false, drawn_ = false;
  std::thread ticker_;
};

}  // namespace depthtrack::cli
