// The command line's progress: a bar and notes above it on a terminal, nothing but the notes elsewhere,
// and a wait line that appears after its delay and leaves the time taken.
#include <catch2/catch.hpp>
#include <cstdio>
#include <regex>
#include <thread>

#include "cli/progress.hpp"

using namespace depthtrack::cli;
using namespace std::chrono_literals;

namespace {

// What was written to f.
std::string written(std::FILE* f) {
  std::fflush(f);
  std::rewind(f);
  std::string text;
  for (int c; (c = std::fgetc(f)) != EOF;) text += static_cast<char>(c);
  std::fclose(f);
  return text;
}

}  // namespace

TEST_CASE("a progress bar draws on a terminal, with notes above it", "[cli][progress]") {
  std::FILE* terminal = std::tmpfile();
  {
    ProgressBar bar("steps", 4, {terminal, true, 0ms});
    bar.update(2, "cpu");
    bar.note("case done");
    bar.update(4);
  }
  const std::string half = "\rsteps [" + std::string(15, '#') + std::string(15, ' ') + "] 2/4 cpu\033[K";
  CHECK(written(terminal) ==
        half + "\r\033[Kcase done\n" + half + "\rsteps [" + std::string(30, '#') + "] 4/4 \033[K\n");

  std::FILE* file = std::tmpfile();
  {
    ProgressBar bar("steps", 4, {file, false, 0ms});
    bar.update(2);
    bar.note("case done");
  }
  CHECK(written(file) == "case done\n");  // the notes only

  std::FILE* early = std::tmpfile();
  {
    ProgressBar bar("steps", 4, {early, true, 10s});
    bar.update(1);
  }
  CHECK(written(early).empty());  // not yet due
}

TEST_CASE("a wait line appears after its delay and leaves the time it took", "[cli][progress]") {
  std::FILE* terminal = std::tmpfile();
  {
    ProgressWait wait("searching", {terminal, true, 50ms});
    std::this_thread::sleep_for(1200ms);
  }
  const std::string text = written(terminal);
  INFO(text);
  CHECK(text.rfind("\rsearching... 0 s\033[K\rsearching... 1 s\033[K", 0) == 0);
  CHECK(std::regex_search(text, std::regex("\rsearching: 1\\.[0-9] s\033\\[K\n$")));

  std::FILE* quick = std::tmpfile();
  { ProgressWait wait("quick", {quick, true, 10s}); }
  CHECK(written(quick).empty());

  std::FILE* file = std::tmpfile();
  {
    ProgressWait wait("redirected", {file, false, 0ms});
    std::this_thread::sleep_for(50ms);
  }
  CHECK(written(file).empty());
}
