#include "tools/kelvin/commands.h"

namespace kelvin::cli {

std::vector<Command> AddCommands(CLI::App& app) {
  std::vector<Command> commands;
  (void)app;
  return commands;
}

}  // namespace kelvin::cli
