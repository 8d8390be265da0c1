#pragma once
// Exceptions that carry a message meant for the user; processes print it and exit non-zero.

#include <stdexcept>
#include <string>

namespace uavmot {

// Bad user input: missing or corrupt files, invalid options or configuration.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Results could not be written (a full disk, an I/O error): the run fails, and what was written
// before stays valid. The message names the file and the system's reason.
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// An argument outside its documented domain (programming or configuration error).
class InvalidArgument : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

}  // namespace uavmot
