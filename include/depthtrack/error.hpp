#pragma once
/// @file
/// Every failure depthtrack reports is one of these: the message names the problem and where it is.
#include <stdexcept>
#include <string>

namespace depthtrack {

/// The base of every error depthtrack throws; what() is the message.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Bad input from the user: files, images, meshes, intrinsics, configuration, timestamps.
class InputError : public Error {
 public:
  using Error::Error;
};

/// A failure of a compute, GL or system API: carries the call and the symbolic error name.
class BackendError : public Error {
 public:
  using Error::Error;
};

}  // namespace depthtrack
