// The kelvin subcommands. Each Add*Command registers a subcommand and its
// options on the app and returns what main() runs when that subcommand was
// given. Commands throw kelvin::ArgumentError for bad arguments (exit 2) and
// kelvin::InputError for bad files (exit 1).
#pragma once

#include <CLI/CLI.hpp>
#include <filesystem>
#include <functional>
#include <vector>

namespace kelvin::cli {

struct Command {
  CLI::App* app = nullptr;
  std::function<void()> run;
};

Command AddSimulateCommand(CLI::App& app);
Command AddCheckCommand(CLI::App& app);
Command AddHullCommand(CLI::App& app);
Command AddCaptiveCommand(CLI::App& app);
Command AddBridgeCommand(CLI::App& app);
Command AddMeshCommand(CLI::App& app);
Command AddRunCommand(CLI::App& app);
Command AddGciCommand(CLI::App& app);
Command AddIdentifyCommand(CLI::App& app);
Command AddListenCommand(CLI::App& app);

// Every subcommand, in the order `kelvin --help` lists them.
std::vector<Command> AddCommands(CLI::App& app);

// The running kelvin program (/proc/self/exe; empty if unknown), which the
// campaigns start as worker processes.
std::filesystem::path SelfExecutable();

// The MPI launcher for `--np np` (mpiexec on PATH; allowed to run as root when
// kelvin does, and to start more ranks than the machine has cores, with a
// warning). Throws ArgumentError naming --np when there is none.
std::filesystem::path FindLauncher(int np);

// Ranks an MPI launcher started this process among (Open MPI's and the PMI
// variables), 1 without one.
int LauncherRanks();

}  // namespace kelvin::cli
