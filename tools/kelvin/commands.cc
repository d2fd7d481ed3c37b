#include "tools/kelvin/commands.h"

#include <algorithm>
#include <cstdlib>
#include <exception>
#include <string>

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
