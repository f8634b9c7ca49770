// planesketch: the executable. With no subcommand it runs the interactive window (where the
// window command is built in); subcommands are registered by app/cmd_*.cpp.
#include <algorithm>
#include <iostream>
#include <vector>

#include "app/commands.h"

namespace ps::app {
namespace {
std::vector<std::pair<int, CommandSetup>>& registry() {
  static std::vector<std::pair<int, CommandSetup>> r;
  return r;
}
}  // namespace

bool register_command(int order, CommandSetup setup) {
  registry().emplace_back(order, setup);
  return true;
}

void run_registered_commands(CLI::App& root) {
  auto r = registry();
  std::stable_sort(r.begin(), r.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (const auto& [order, setup] : r) setup(root);
}

}  // namespace ps::app

int main(int argc, char** argv) {
  CLI::App app{"planesketch: pen-first 3D modeling from cross sections on reference planes"};
  app.set_version_flag("--version", "planesketch 0.1");
  app.require_subcommand(0, 1);
  ps::app::run_registered_commands(app);
  try {
    app.parse(argc, argv);
    if (app.get_subcommands().empty()) {
      std::cout << app.help();
      return 0;
    }
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const ps::app::CommandFailed& e) {
    std::cerr << "planesketch: " << e.what() << "\n";
    return e.code;
  } catch (const std::exception& e) {
    std::cerr << "planesketch: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
