// prm: the command-line tool. One sub-command per cmd_<name>.cpp; see commands.h.
#include <cmath>
#include <cstdio>
#include <exception>
#include <new>
#include <string>

#include "commands.h"
#include "exit_codes.h"
#include "prm/error.h"

namespace {

// Every floating-point option of every command refuses NaN and the infinities by name: CLI11's range checks let NaN
// through (no comparison with it is true), and a NaN grid or weight would otherwise reach the library.
void refuse_non_finite_numbers(CLI::App& app) {
  const CLI::Validator finite(
      [](std::string& text) -> std::string {
        try {
          const double v = std::stod(text);
          if (!std::isfinite(v)) return "must be a finite number, got " + text;
        } catch (const std::exception&) {
          // not a number at all: the option's own conversion says so
        }
        return {};
      },
      "", "FINITE");
  for (CLI::Option* opt : app.get_options())
    if (opt->get_type_name().rfind("FLOAT", 0) == 0) opt->check(finite);
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) refuse_non_finite_numbers(*sub);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace prm::cli;
  CLI::App app{"prm: piecewise regular meshes (remesh, compress, inspect, compare)"};
  app.require_subcommand(1);
  app.fallthrough();
  app.footer(
      "Exit codes: 0 success, 1 bad command line, 2 invalid input (malformed, truncated or lying file,\n"
      "unsupported mesh), 3 the work could not be done, 4 a file could not be read or written.\n"
      "Run `prm <command> --help` for the options of a command.");
  app.set_version_flag("--version", "prm 0.1.0");

  add_info_command(app);
  add_compare_command(app);
  add_repair_command(app);
  add_reliefs_command(app);
  add_render_command(app);
  add_remesh_command(app);
  add_encode_command(app);
  add_decode_command(app);
  add_pack_command(app);
  add_unpack_command(app);
  refuse_non_finite_numbers(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kExitUsage;
  } catch (const prm::InputError& e) {
    std::fprintf(stderr, "prm: error: %s\n", e.what());
    return kExitBadInput;
  } catch (const prm::IoError& e) {
    std::fprintf(stderr, "prm: error: %s\n", e.what());
    return kExitIo;
  } catch (const Failure& e) {
    std::fprintf(stderr, "prm: failed: %s\n", e.what());
    return kExitFailed;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "prm: error: out of memory\n");
    return kExitFailed;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "prm: internal error: %s\n", e.what());
    return kExitInternal;
  }
  return kExitOk;
}
