// planesketch: the executable. With no subcommand it runs the interactive window (where the
// window command is built in); subcommands are registered by app/cmd_*.cpp.
#include <algorithm>
#include <iostream>
#include <string>
#include <vector>

#include "app/commands.h"
#include "app/journal.h"
#include "modeling/allocator_policy.h"

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
  ps::keep_freed_memory();  // modeling/allocator_policy.h
  CLI::App app{"planesketch: pen-first 3D modeling from cross sections on reference planes"};
  app.set_version_flag("--version", "planesketch 0.1");
  app.require_subcommand(0, 1);
  app.footer("Crash recovery: planesketch --recover [JOURNAL] [-o MESH] is 'planesketch recover'.");
  ps::app::run_registered_commands(app);
  // `planesketch --recover [JOURNAL] ...` is spelled as the issue asks; it is the `recover`
  // subcommand (`--recover=JOURNAL` too).
  std::vector<std::string> args(argv, argv + argc);
  if (args.size() > 1 && args[1] == "--recover") {
    args[1] = "recover";
  } else if (args.size() > 1 && args[1].rfind("--recover=", 0) == 0) {
    const std::string path = args[1].substr(10);
    args[1] = "recover";
    args.insert(args.begin() + 2, path);
  }
  std::vector<char*> cargs;
  for (auto& a : args) cargs.push_back(a.data());
  try {
    app.parse(static_cast<int>(cargs.size()), cargs.data());
    if (app.get_subcommands().empty()) {
      std::cout << app.help();
      // The next start offers to recover a session that died.
      if (const auto j = ps::app::newest_unfinished_journal(ps::app::journal_dir()))
        std::cerr << "planesketch: an unfinished session journal is waiting: " << j->path.string()
                  << "\nplanesketch: recover it with: planesketch --recover -o recovered.obj\n";
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
