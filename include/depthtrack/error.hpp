#pragma once
// Every failure depthtrack reports is one of these: the message names the problem and where it is.
#include <stdexcept>
#include <string>

namespace depthtrack {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Bad input from the user: files, images, meshes, intrinsics, configuration, timestamps.
class InputError : public Error {
 public:
  using Error::Error;
};

// A failure of a compute, GL or system API: carries the call and the symbolic error name.
class BackendError : public Error {
 public:
  using Error::Error;
};

}  // namespace depthtrack
