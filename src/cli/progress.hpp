#pragma once
// A one-line progress bar on stderr, drawn only when stderr is a terminal.
#include <unistd.h>

#include <cstdio>
#include <string>

namespace depthtrack::cli {

class ProgressBar {
 public:
  ProgressBar(std::string label, int total) : label_(std::move(label)), total_(total), enabled_(isatty(2) != 0) {}
  ~ProgressBar() { finish(); }
  void update(int done, const std::string& suffix = "") {
    if (!enabled_ || total_ <= 0) return;
    const int width = 30, filled = done * width / total_;
    std::fprintf(stderr, "\r%s [%s%s] %d/%d %s\033[K", label_.c_str(),
                 std::string(static_cast<size_t>(filled), '#').c_str(),
                 std::string(static_cast<size_t>(width - filled), ' ').c_str(), done, total_, suffix.c_str());
    std::fflush(stderr);
    drawn_ = true;
  }
  void finish() {
    if (drawn_) std::fprintf(stderr, "\n");
    drawn_ = false;
  }

 private:
  std::string label_;
  int total_;
  bool enabled_;
  bool drawn_ = false;
};

}  // namespace depthtrack::cli
