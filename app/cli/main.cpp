// aggpack: random aggregate generation, packing and export. See README.md for every command.

#include <cstdio>
#include <exception>

#include <CLI/CLI.hpp>

#include "aggpack/core/error.h"
#include "aggpack/core/temp_paths.h"
#include "aggpack/core/text.h"
#include "commands.h"
#include "progress.h"

int main(int argc, char** argv) {
  CLI::App app{"aggpack " AGGPACK_VERSION
               ": irregular convex particles (random aggregate growth), packing and export.\n"
               "Lengths are in metres unless an option says otherwise."};
  app.set_version_flag("--version", "aggpack " AGGPACK_VERSION);
  app.require_subcommand(1);
  // A bad AGGPACK_PROGRESS_DELAY is refused once the command line is read (help and --version
  // still work), before the command runs: not minutes later, when a first timed stage starts.
  app.parse_complete_callback([] { (void)aggpack::cli::progress_delay(); });
  aggpack::cli::register_particle(app);
  aggpack::cli::register_shapes(app);
  aggpack::cli::register_calibrate(app);
  aggpack::cli::register_pack(app);
  aggpack::cli::register_info(app);
  aggpack::cli::register_densify(app);
#ifdef AGGPACK_HAS_RENDER
  aggpack::cli::register_render(app);
#endif
  aggpack::cli::register_export(app);
  aggpack::cli::register_mesomodel(app);
  aggpack::cli::register_config_keys(app);
#ifdef AGGPACK_HAS_SIM
  aggpack::cli::register_sim(app);
#endif
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return app.exit(error);
  } catch (const aggpack::Error& error) {
    aggpack::wait_if_terminating();
    // One line, bounded: whatever input a message echoes (the parts that echo input clip it
    // already; this is the net).
    std::fprintf(stderr, "aggpack: error: %s\n", aggpack::clipped(error.what(), 1000).c_str());
    return error.kind() == aggpack::ErrorKind::kIoError ? 3 : 2;
  } catch (const std::exception& error) {
    aggpack::wait_if_terminating();
    std::fprintf(stderr, "aggpack: internal error: %s\n",
                 aggpack::clipped(error.what(), 1000).c_str());
    return 4;
  }
  aggpack::wait_if_terminating();
  return 0;
}
