// Exit codes of the prm tool (also listed in `prm --help`, the README and docs/cli-json.md, whose error object
// carries the code and a name for it).
#pragma once

namespace prm::cli {

enum ExitCode : int {
  kExitOk = 0,          // success
  kExitUsage = 1,       // bad command line (unknown option, missing argument, value out of range)
  kExitBadInput = 2,    // the input is malformed, lies about itself, or is not a mesh this command accepts
  kExitFailed = 3,      // the input was fine but the work could not be done (e.g. a target error not reached)
  kExitIo = 4,          // a file could not be opened, read or written (a missing input file, in every command)
  kExitInternal = 70,   // a bug: an unexpected exception escaped
};

}  // namespace prm::cli
