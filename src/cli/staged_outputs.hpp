#pragma once
// The files one command writes, checked before any work and replaced together at the end, so that a
// failure anywhere (a bad path, a full disk, an error mid-run) leaves every earlier file as it was.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "core/partial_files.hpp"

namespace depthtrack::cli {

class StagedOutputs {
 public:
  StagedOutputs() = default;
  StagedOutputs(const StagedOutputs&) = delete;
  StagedOutputs& operator=(const StagedOutputs&) = delete;
  // Removes the partial files of a run that did not commit.
  ~StagedOutputs();

  // A file the command reads: no output may name it (checked for the outputs added before and after).
  void add_input(const std::filesystem::path& path);
  // Checks path, the value of option: not empty, not a folder, in a folder that exists, not an input,
  // not another output. Returns where to write it: PATH.partial beside it, or PATH itself for a
  // device such as /dev/stdout or /dev/full, which cannot be replaced.
  std::filesystem::path add(const std::string& option, const std::filesystem::path& path);
  // Renames every partial file over its path, all or none: an earlier file is first moved aside
  // (PATH.previous), and put back if a later rename fails.
  void commit();

 private:
  struct Output {
    std::string option;
    std::filesystem::path path, partial;
    PartialFile listed;  // the partial file, removed if the run is interrupted
  };
  std::vector<Output> outputs_;
  // By absolute, symlink-resolved path: the input's path as given, the output's index.
  std::map<std::filesystem::path, std::filesystem::path> inputs_;
  std::map<std::filesystem::path, size_t> output_keys_;
  bool committed_ = false;
};

// Writes text to path, checking every write, the flush and the close; Error naming the file otherwise.
void write_text_file(const std::filesystem::path& path, const std::string& text);

}  // namespace depthtrack::cli
