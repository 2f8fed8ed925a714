// Error types of the tools, the remesher and the I/O layer. (The codec returns status codes instead.)
// The command-line tool maps them to exit codes: tools/prm/exit_codes.h.
#pragma once

#include <stdexcept>
#include <string>

namespace prm {

// The input (a file, a mesh, a parameter value) is malformed, lies about itself or cannot be processed
// as given. The message names the problem and, where it applies, the file and the position in it.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Reading or writing a file failed at the operating-system level (missing, unreadable, disk full).
class IoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace prm
