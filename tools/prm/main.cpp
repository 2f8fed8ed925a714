// prm: the command-line tool. One sub-command per cmd_<name>.cpp; see commands.h.
#include <cmath>
#include <unistd.h>

#include <cstdio>
#include <exception>
#include <new>
#include <string>

#include "commands.h"
#include "exit_codes.h"
#include "json_report.h"
#include "prm/error.h"
#include "prm/progress.h"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace {

// glibc's malloc raises its mmap threshold to the size of the largest mapped block freed (up to 32 MiB); after that
// the remesher's large, short-lived arrays (sliced reliefs, OpenMesh kernels, tree scratch) come from the heaps of
// its threads, which keep the freed pages. A fixed threshold maps every block of 1 MiB or more and unmaps it when
// freed: measured on the 537k-vertex igea, `prm remesh` peaks at 291 MB instead of 380 MB, for ~0.85 s more system
// time in 20 s (bench/README.md "Scale"). The heaps grow and shrink by at least 32 MiB (M_TOP_PAD; glibc's default
// is 128 KiB), so that the smaller blocks' pages are not returned and faulted in again at every step: `pack --effort
// 0` of the venus spent 0.26-0.39 s of its ~4.1 s CPU in the kernel, 0.08-0.11 s with the pad, for 8-17 MB more peak
// (issue 21, bench/README.md "pack effort").
void map_large_blocks() {
#if defined(__GLIBC__)
  mallopt(M_MMAP_THRESHOLD, 1 << 20);
  mallopt(M_TOP_PAD, 32 << 20);
#endif
}

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

// `flag` anywhere on the command line (before parsing: it decides how errors and progress are reported).
bool has_flag(int argc, char** argv, const char* flag) {
  for (int i = 1; i < argc; ++i)
    if (std::string(argv[i]) == flag) return true;
  return false;
}

// --quiet: no progress line and no report on stdout (a --json report is still printed: it was asked for);
// --progress: the progress line even when stderr is not a terminal, there as JSON lines (docs/cli-json.md
// "Progress"); neither: the line on a terminal only.
void set_up_progress(bool quiet, bool progress, bool json) {
  if (quiet) {
    prm::Progress::set_mode(prm::ProgressMode::off);
    if (!json && !std::freopen("/dev/null", "w", stdout)) std::fclose(stdout);
  } else if (progress) {
    prm::Progress::set_mode(isatty(STDERR_FILENO) ? prm::ProgressMode::terminal : prm::ProgressMode::json,
                            prm::cli::kJsonSchemaVersion);
  }
}

// One error: the text line on stderr, and with --json the error object (docs/cli-json.md "Errors") after it.
int report_error(bool json, int code, const char* name, const char* prefix, const std::string& message) {
  prm::Progress::clear();
  std::fprintf(stderr, "prm: %s: %s\n", prefix, message.c_str());
  if (json) std::fprintf(stderr, "%s\n", prm::cli::error_json(code, name, message).c_str());
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace prm::cli;
  map_large_blocks();
  CLI::App app{"prm: piecewise regular meshes (remesh, compress, inspect, compare)"};
  app.require_subcommand(1);
  app.fallthrough();
  app.footer(
      "Exit codes: 0 success, 1 bad command line, 2 invalid input (malformed, truncated or lying file,\n"
      "unsupported mesh), 3 the work could not be done, 4 a file could not be read or written (a missing input\n"
      "file in every command). With --json, an error is also one JSON object on stderr (docs/cli-json.md).\n"
      "Run `prm <command> --help` for the options of a command.");
  app.set_version_flag("--version", "prm 0.1.0");
  auto* quiet = app.add_flag("--quiet", "Print nothing but errors: no progress line, no report on stdout (a --json "
                                        "report is still printed)");
  auto* progress = app.add_flag("--progress", "Show the progress line even when stderr is not a terminal: there as "
                                              "JSON lines on stderr (docs/cli-json.md \"Progress\")");
  quiet->excludes(progress);

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

  const bool json = has_flag(argc, argv, "--json");
  set_up_progress(has_flag(argc, argv, "--quiet"), has_flag(argc, argv, "--progress"), json);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ValidationError& e) {
    // CLI::ExistingFile's refusal: a missing input is an I/O error (exit 4) in every command, as the readers say.
    if (std::string(e.what()).find("File does not exist") != std::string::npos)
      return report_error(json, kExitIo, "io", "error", e.what());
    if (!json) {
      app.exit(e);
      return kExitUsage;
    }
    return report_error(json, kExitUsage, "usage", "error", e.what());
  } catch (const CLI::ParseError& e) {
    if (!json) {
      app.exit(e);
      return kExitUsage;
    }
    return report_error(json, kExitUsage, "usage", "error", e.what());
  } catch (const prm::InputError& e) {
    return report_error(json, kExitBadInput, "bad_input", "error", e.what());
  } catch (const prm::IoError& e) {
    return report_error(json, kExitIo, "io", "error", e.what());
  } catch (const Failure& e) {
    return report_error(json, kExitFailed, "failed", "failed", e.what());
  } catch (const std::bad_alloc&) {
    return report_error(json, kExitFailed, "out_of_memory", "error", "out of memory");
  } catch (const std::exception& e) {
    return report_error(json, kExitInternal, "internal", "internal error", e.what());
  }
  return kExitOk;
}
