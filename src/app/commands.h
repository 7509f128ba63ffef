// Each ddish command lives in its own cmd_NAME.cpp and registers itself here with
// DDISH_COMMAND(order, factory): the factory adds a CLI11 subcommand with its options and returns
// the function that runs it. Errors in user input are thrown as std::exception and reported by
// main as one line on stderr with exit code 2.
#pragma once

#include <functional>
#include <vector>

namespace CLI {
class App;
}

namespace ddish::app {

using Action = std::function<int()>;  // runs the command, returns the exit code
using CommandFactory = Action (*)(CLI::App& root);

struct CommandEntry {
  int order;  // position in --help
  CommandFactory factory;
};

std::vector<CommandEntry>& command_registry();

struct CommandRegistrar {
  CommandRegistrar(int order, CommandFactory factory) {
    command_registry().push_back({order, factory});
  }
};

}  // namespace ddish::app

#define DDISH_COMMAND(order, factory) \
  static const ::ddish::app::CommandRegistrar ddish_command_registrar_##order{order, factory}
