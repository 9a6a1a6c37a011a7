#include "core/partial_files.hpp"

#include <unistd.h>

#include <array>
#include <atomic>
#include <climits>
#include <csignal>
#include <cstring>

namespace depthtrack {

namespace {

constexpr int kSlots = 64;

// A slot is claimed (claimed = true) by one owner, filled, then published (listed = true); the signal
// handler reads only published slots, with nothing but unlink(), which is async-signal-safe.
struct Slot {
  std::atomic<bool> claimed{false};
  std::atomic<bool> listed{false};
  char path[PATH_MAX];
};

std::array<Slot, kSlots>& slots() {
  static std::array<Slot, kSlots> table;
  return table;
}

int list_path(const std::filesystem::path& path) {
  const std::string& text = path.native();
  if (text.empty() || text.size() >= PATH_MAX) return -1;
  for (int i = 0; i < kSlots; ++i) {
    Slot& slot = slots()[static_cast<size_t>(i)];
    bool expected = false;
    if (!slot.claimed.compare_exchange_strong(expected, true)) continue;
    std::memcpy(slot.path, text.c_str(), text.size() + 1);
    slot.listed.store(true);
    return i;
  }
  return -1;
}

void unlist(int i) {
  if (i < 0) return;
  Slot& slot = slots()[static_cast<size_t>(i)];
  slot.listed.store(false);
  slot.claimed.store(false);
}

extern "C" void remove_partial_files_and_die(int signal_number) {
  for (Slot& slot : slots())
    if (slot.listed.load()) ::unlink(slot.path);
  std::signal(signal_number, SIG_DFL);
  std::raise(signal_number);
}

}  // namespace

PartialFile::PartialFile(const std::filesystem::path& path) : slot_(list_path(path)) {}

PartialFile::~PartialFile() {
  release();
}

PartialFile::PartialFile(PartialFile&& other) noexcept : slot_(other.slot_) {
  other.slot_ = -1;
}

PartialFile& PartialFile::operator=(PartialFile&& other) noexcept {
  if (this != &other) {
    release();
    slot_ = other.slot_;
    other.slot_ = -1;
  }
  return *this;
}

void PartialFile::release() {
  unlist(slot_);
  slot_ = -1;
}

void remove_partial_files_on_interrupt() {
  static const bool installed = [] {
    struct sigaction action {};
    action.sa_handler = remove_partial_files_and_die;
    sigemptyset(&action.sa_mask);
    for (const int signal_number : {SIGINT, SIGTERM, SIGHUP}) {
      struct sigaction before {};
      ::sigaction(signal_number, nullptr, &before);
      // A signal the caller chose to ignore (nohup, a background job) stays ignored.
      if (before.sa_handler != SIG_IGN) ::sigaction(signal_number, &action, nullptr);
    }
    return true;
  }();
  (void)installed;
}

}  // namespace depthtrack
