#pragma once
// Subcommands register themselves: each app/cmd_*.cpp adds one with PLANESKETCH_COMMAND, so the
// command files stay independent of each other and of main.cpp.
//
// A command's setup function adds a CLI11 subcommand to `root` and sets its callback. The
// callback reports failure by throwing CommandFailed (message printed as one line on stderr,
// exit status `code`); it never exits the process itself.
#include <CLI/CLI.hpp>
#include <stdexcept>
#include <string>

namespace ps::app {

struct CommandFailed : std::runtime_error {
  int code;
  explicit CommandFailed(const std::string& message, int exit_code = 1)
      : std::runtime_error(message), code(exit_code) {}
};

using CommandSetup = void (*)(CLI::App& root);
bool register_command(int order, CommandSetup setup);
// Set by main before parsing: true when the top level ran a subcommand.
void run_registered_commands(CLI::App& root);

}  // namespace ps::app

#define PLANESKETCH_COMMAND(order, fn) \
  static const bool planesketch_registered_##fn = ::ps::app::register_command(order, fn)
