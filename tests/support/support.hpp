#pragma once
// Shared helpers of the test suite.
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>

namespace depthtrack::test {

// Path of a file under ../shared/data, or nullopt (after printing "SKIPPED: ...", which ctest
// reports as a skip) when the third-party data is not there, as in a user's fresh clone.
inline std::optional<std::filesystem::path> shared_data(const std::string& relative) {
  const char* env = std::getenv("DEPTHTRACK_DATA_DIR");
  const std::filesystem::path root = env ? env : DEPTHTRACK_DATA_DIR;
  const auto path = root / relative;
  if (std::filesystem::exists(path)) return path;
  std::cout << "SKIPPED: " << path.string() << " is absent (third-party data lives in ../shared/data)\n";
  return std::nullopt;
}

// A fresh, empty folder for one test's files, inside the build tree, or under DEPTHTRACK_TEST_TMP
// when set (test runs side by side, e.g. one per device, each with its own).
inline std::filesystem::path temp_dir(const std::string& name) {
  const char* env = std::getenv("DEPTHTRACK_TEST_TMP");
  const auto dir = std::filesystem::path(env && *env ? env : DEPTHTRACK_TEST_TMP) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// Runs the depthtrack command with arguments, its output (stdout and stderr) to log; returns the
// exit status and the output.
inline std::pair<int, std::string> run_cli(const std::string& arguments, const std::filesystem::path& log,
                                           const std::string& environment = "") {
  const std::string command = (environment.empty() ? "" : "env " + environment + " ") + std::string(DEPTHTRACK_CLI) +
                              " " + arguments + " > " + log.string() + " 2>&1";
  const int status = std::system(command.c_str());
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text.str()};
}

}  // namespace depthtrack::test
