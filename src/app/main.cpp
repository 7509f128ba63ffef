// ddish: multi-view rendering with path-traced SH light probes (DDISH-GI). See README.md.
#include <algorithm>
#include <cstdio>
#include <exception>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/commands.h"
#include "app/interrupt.h"

namespace ddish::app {
std::vector<CommandEntry>& command_registry() {
  static std::vector<CommandEntry> registry;
  return registry;
}
}  // namespace ddish::app

int main(int argc, char** argv) {
  ddish::app::install_interrupt_handlers();
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

  // CLI11 takes an unknown word for a stray positional: it would print the main help for
  // `ddish nosuch --help` and say "A subcommand is required" for `ddish nosuch`. The root has
  // flags only, so its first non-option argument is the command.
  for (int i = 1; i < argc; ++i) {
    const std::string word = argv[i];
    if (word.empty() || word[0] == '-') continue;
    if (std::none_of(commands.begin(), commands.end(),
                     [&](const auto& c) { return c.first->get_name() == word; })) {
      std::string names;
      for (const auto& c : commands) names += (names.empty() ? "" : ", ") + c.first->get_name();
      std::fprintf(stderr, "ddish: error: unknown command '%s' (commands: %s; see ddish --help)\n",
                   word.c_str(), names.c_str());
      return 2;
    }
    break;
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
