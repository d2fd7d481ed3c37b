#include "tools/kelvin/commands.h"

namespace kelvin::cli {

Command AddRunCommand(CLI::App& app);

std::vector<Command> AddCommands(CLI::App& app) {
  std::vector<Command> commands;
  commands.push_back(AddRunCommand(app));
  return commands;
}

}  // namespace kelvin::cli
