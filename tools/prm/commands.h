// Every sub-command of `prm` lives in its own cmd_<name>.cpp and adds itself to the root app here.
// A command's callback does the work and may throw prm::InputError / prm::IoError (mapped to exit codes
// in main.cpp) or prm::cli::Failure (exit code 3).
#pragma once

#include <CLI/CLI.hpp>
#include <stdexcept>

namespace prm::cli {

// The input was valid but the requested work could not be done; exit code kExitFailed.
class Failure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// One line per command, in the order `prm --help` lists them.
void add_info_command(CLI::App& root);
void add_compare_command(CLI::App& root);
void add_repair_command(CLI::App& root);
void add_reliefs_command(CLI::App& root);
void add_render_command(CLI::App& root);
void add_remesh_command(CLI::App& root);
void add_encode_command(CLI::App& root);
void add_decode_command(CLI::App& root);
void add_pack_command(CLI::App& root);
void add_unpack_command(CLI::App& root);

}  // namespace prm::cli
