#pragma once
// Files a run writes beside their final place (PATH.partial) until it commits them. While one exists it is
// listed here, so that an interrupted run (Ctrl-C, SIGTERM, SIGHUP) removes it before it dies: an
// interrupted run leaves every earlier file as it was and no partial file behind.
#include <filesystem>

namespace depthtrack {

// Lists a partial file for as long as it lives. Paths longer than PATH_MAX or beyond the table's 64 slots
// are not listed (the file is still removed by its owner on a normal exit or an error).
class PartialFile {
 public:
  PartialFile() = default;
  explicit PartialFile(const std::filesystem::path& path);
  ~PartialFile();
  PartialFile(PartialFile&& other) noexcept;
  PartialFile& operator=(PartialFile&& other) noexcept;
  PartialFile(const PartialFile&) = delete;
  PartialFile& operator=(const PartialFile&) = delete;

  // Stops listing the file (it was renamed into place or removed).
  void release();

 private:
  int slot_ = -1;
};

// Installs handlers for SIGINT, SIGTERM and SIGHUP that remove every listed partial file, then end the
// process as the signal would have (a shell sees the usual status). A signal ignored when this is called
// stays ignored. Idempotent.
void remove_partial_files_on_interrupt();

}  // namespace depthtrack
