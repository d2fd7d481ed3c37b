#include "tools/kelvin/commands.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <exception>
#include <string>

#include "data/schema/errors.h"

namespace kelvin::cli {

std::vector<Command> AddCommands(CLI::App& app) {
  std::vector<Command> commands;
  // Pipeline order: geometry, captive tests, identification, simulation,
  // the surrogate check, real time.
  commands.push_back(AddHullCommand(app));
  commands.push_back(AddMeshCommand(app));
  commands.push_back(AddRunCommand(app));
  commands.push_back(AddGciCommand(app));
  commands.push_back(AddCaptiveCommand(app));
  commands.push_back(AddIdentifyCommand(app));
  commands.push_back(AddSimulateCommand(app));
  commands.push_back(AddCheckCommand(app));
  commands.push_back(AddBridgeCommand(app));
  commands.push_back(AddListenCommand(app));
  return commands;
}

std::filesystem::path SelfExecutable() {
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::filesystem::path() : self;
}

std::filesystem::path FindLauncher(int np) {
  std::filesystem::path launcher;
  if (const char* path = std::getenv("PATH")) {
    const std::string dirs = path;
    for (std::size_t start = 0; start <= dirs.size();) {
      const std::size_t end = std::min(dirs.find(':', start), dirs.size());
      const std::filesystem::path candidate =
          std::filesystem::path(dirs.substr(start, end - start)) / "mpiexec";
      if (end > start && access(candidate.c_str(), X_OK) == 0) {
        launcher = candidate;
        break;
      }
      start = end + 1;
    }
  }
  if (launcher.empty()) {
    throw ArgumentError(fmt::format(
        "--np {}: no MPI launcher 'mpiexec' on PATH; expected Open MPI's (Debian package "
        "openmpi-bin, which tools/setup installs), or start kelvin under your cluster's "
        "launcher yourself",
        np));
  }
  // Open MPI refuses root unless told; the user asked for the ranks.
  if (geteuid() == 0) {
    setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 0);
    setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 0);
  }
  // It also refuses more ranks than cores (its "slots"): run them, and say
  // that they share the cores.
  if (const long cores = sysconf(_SC_NPROCESSORS_ONLN); cores > 0 && np > cores) {
    setenv("OMPI_MCA_rmaps_base_oversubscribe", "1", 0);
    spdlog::warn("--np {} on a machine with {} cores: the ranks share the cores (oversubscribed), so a step "
                 "takes longer than on {} ranks",
                 np, cores, cores);
  }
  return launcher;
}

int LauncherRanks() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE"}) {
    if (const char* v = std::getenv(name)) {
      try {
        return std::max(1, std::stoi(v));
      } catch (const std::exception&) {
      }
    }
  }
  return 1;
}

}  // namespace kelvin::cli
