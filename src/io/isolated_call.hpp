#pragma once
// Runs a function in a forked child process with a wall-clock limit, so that a third-party parser
// that crashes, aborts or loops (assimp on hostile files) cannot take the caller down: any failure
// becomes an InputError naming `what`.
#include <chrono>
#include <functional>
#include <string>

namespace depthtrack::io {

// work's result (bytes) as the child produced them. An InputError or other exception thrown by work
// in the child is rethrown here as an InputError with its message; a child that dies by a signal,
// exits without an answer or outlives `limit` (it is then killed) gives an InputError naming `what`.
std::string call_isolated(const std::function<std::string()>& work, std::chrono::milliseconds limit,
                          const std::string& what);

}  // namespace depthtrack::io
