#include "io/isolated_call.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <depthtrack/error.hpp>
#include <exception>

namespace depthtrack::io {

namespace {

// Answer format on the pipe: one byte ('+' result, '!' error message), then the bytes.
void write_all(int fd, const char* data, size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) ::_exit(3);
    data += n;
    size -= static_cast<size_t>(n);
  }
}

[[noreturn]] void run_child(const std::function<std::string()>& work, int fd) {
  // A crash ends the child at once: the parent's crash handlers (a test framework's, say) must not
  // run here, and no core file is needed for a crash the parent reports anyway.
  for (const int s : {SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGABRT}) ::signal(s, SIG_DFL);
  const rlimit no_core{0, 0};
  ::setrlimit(RLIMIT_CORE, &no_core);
  char tag = '+';
  std::string answer;
  try {
    answer = work();
  } catch (const std::exception& e) {
    tag = '!';
    answer = e.what();
  } catch (...) {
    tag = '!';
    answer = "unknown error";
  }
  write_all(fd, &tag, 1);
  write_all(fd, answer.data(), answer.size());
  ::close(fd);
  ::_exit(0);  // no atexit handlers, no flushing of the parent's buffers a second time
}

std::string describe_status(int status) {
  if (WIFSIGNALED(status)) {
    const char* name = ::strsignal(WTERMSIG(status));
    return std::string("crashed (signal ") + std::to_string(WTERMSIG(status)) + ", " + (name ? name : "?") + ")";
  }
  if (WIFEXITED(status)) return "exited with status " + std::to_string(WEXITSTATUS(status)) + " without an answer";
  return "ended abnormally";
}

}  // namespace

std::string call_isolated(const std::function<std::string()>& work, std::chrono::milliseconds limit,
                          const std::string& what) {
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) throw Error(what + ": pipe failed: " + std::strerror(errno));
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    throw Error(what + ": fork failed: " + std::strerror(errno));
  }
  if (pid == 0) {
    ::close(fds[0]);
    run_child(work, fds[1]);
  }
  ::close(fds[1]);

  std::string received;
  bool timed_out = false;
  const auto deadline = std::chrono::steady_clock::now() + limit;
  char buffer[65536];
  for (;;) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      timed_out = true;
      break;
    }
    pollfd p{fds[0], POLLIN, 0};
    const int ready = ::poll(&p, 1, static_cast<int>(std::min<long long>(left.count(), 1000)));
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) continue;
    const ssize_t n = ::read(fds[0], buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // end of the answer (or the child died)
    received.append(buffer, static_cast<size_t>(n));
  }
  ::close(fds[0]);
  if (timed_out) ::kill(pid, SIGKILL);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (timed_out)
    throw InputError(what + ": gave no answer within " + std::to_string(limit.count() / 1000.0).substr(0, 4) +
                     " s (its importer was stopped; the file is likely malformed)");
  const bool clean_exit = WIFEXITED(status) && WEXITSTATUS(status) == 0;
  if (!clean_exit || received.empty())
    throw InputError(what + ": its importer " + describe_status(status) + " reading it (the file is likely malformed)");
  if (received[0] == '!') throw InputError(received.substr(1));
  return received.substr(1);
}

}  // namespace depthtrack::io
