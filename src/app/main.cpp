// ddish: multi-view rendering with path-traced SH light probes (DDISH-GI). See README.md.
#include <algorithm>
#include <cstdio>
#include <exception>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/commands.h"

namespace ddish::app {
std::vector<CommandEntry>& command_registry() {
  static std::vector<CommandEntry> registry;
  return registry;
}
}  // namespace ddish::app

int main(int argc, char** argv) {
  CLI::App app{"ddish: multi-view rendering with path-traced spherical-harmonics light probes"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "ddish 0.1.0");

  auto entries = ddish::app::command_registry();
  std::sort(entries.begin(), entries.end(),
            [](const auto& a, const auto& b) { return a.order < b.order; });
  std::vector<std::pair<CLI::App*, ddish::app::Action>> commands;
  for (const auto& entry : entries) {
    std::size_t before = app.get_subcommands({}).size();
    ddish::app::Action action = entry.factory(app);
    commands.emplace_back(app.get_subcommands({}).at(before), std::move(action));
  }

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "ddish: error: %s (see ddish --help)\n", e.what());
    return 2;
  }

  try {
    for (auto& [sub, action] : commands)
      if (sub->parsed()) return action();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ddish: error: %s\n", e.what());
    return 2;
  }
  return 2;
}
