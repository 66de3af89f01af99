#pragma once
// Each command file of the isomuscle executable registers its subcommands here through a static
// CommandRegistration object, so adding a command never edits main.cpp.
#include <CLI/CLI.hpp>
#include <functional>
#include <vector>

namespace isomuscle::app {

// Adds subcommands to the top-level app. The callback stored by a subcommand must return the
// process exit code through set_exit_code().
using CommandInstaller = std::function<void(CLI::App& app)>;

std::vector<CommandInstaller>& command_installers();
void set_exit_code(int code);
int exit_code();

struct CommandRegistration {
  explicit CommandRegistration(CommandInstaller installer) {
    command_installers().push_back(std::move(installer));
  }
};

}  // namespace isomuscle::app
