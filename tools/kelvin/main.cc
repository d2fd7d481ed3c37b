// kelvin: from hull CFD to real-time maneuvering. One program, one subcommand
// per pipeline stage; see `kelvin --help`.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "data/report/log.h"
#include "data/schema/errors.h"
#include "tools/kelvin/commands.h"

#ifndef KELVIN_VERSION
#define KELVIN_VERSION "unknown"
#endif


int main(int argc, char** argv) {
  CLI::App app{"kelvin: linearized free-surface CFD, MMG identification and real-time maneuvering", "kelvin"};
  app.set_version_flag("--version", std::string("kelvin ") + KELVIN_VERSION);
  app.require_subcommand(0, 1);
  bool verbose = false;
  bool quiet = false;
  app.add_flag("-v,--verbose", verbose, "More log output");
  app.add_flag("-q,--quiet", quiet, "Only warnings and errors");

  const std::vector<kelvin::cli::Command> commands = kelvin::cli::AddCommands(app);

  std::string help_topic;
  CLI::App* help = app.add_subcommand("help", "Show help for a subcommand: kelvin help <command>");
  help->add_option("command", help_topic, "Subcommand to describe");

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "kelvin: error: %s (see 'kelvin --help')\n", e.what());
    return 2;
  }

  if (app.get_subcommands().empty()) {
    std::fprintf(stderr, "kelvin: error: no command given (see 'kelvin --help')\n");
    return 2;
  }
  if (help->parsed()) {
    if (help_topic.empty()) {
      std::fputs(app.help().c_str(), stdout);
      return 0;
    }
    for (CLI::App* sub : app.get_subcommands({})) {
      if (sub->get_name() == help_topic) {
        std::fputs(sub->help().c_str(), stdout);
        return 0;
      }
    }
    std::fprintf(stderr, "kelvin: error: unknown command '%s' (see 'kelvin --help')\n", help_topic.c_str());
    return 2;
  }

  // Under an MPI launcher only `kelvin run` and the captive campaign's
  // workers (`kelvin captive --run`, which checks itself) decompose their
  // case; every rank of any other command would do the whole work and write
  // the same files.
  if (const int ranks = kelvin::cli::LauncherRanks(); ranks > 1) {
    for (CLI::App* sub : app.get_subcommands()) {
      if (sub->get_name() == "run" || sub->get_name() == "captive") continue;
      std::fprintf(stderr,
                   "kelvin: error: kelvin %s was started by an MPI launcher on %d ranks; only 'kelvin run' and the "
                   "workers of 'kelvin captive --np' run on MPI ranks (cfd/README.md 'MPI ranks'); expected one "
                   "process (start it without mpirun)\n",
                   sub->get_name().c_str(), ranks);
      return 2;
    }
  }
  kelvin::InitLogging(quiet ? kelvin::Verbosity::kQuiet
                            : (verbose ? kelvin::Verbosity::kVerbose : kelvin::Verbosity::kNormal));
  try {
    for (const auto& cmd : commands) {
      if (cmd.app->parsed()) cmd.run();
    }
  } catch (const kelvin::ArgumentError& e) {
    std::fprintf(stderr, "kelvin: error: %s\n", e.what());
    return 2;
  } catch (const kelvin::InputError& e) {
    std::fprintf(stderr, "kelvin: error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "kelvin: failed: %s\n", e.what());
    return 1;
  }
  return 0;
}
