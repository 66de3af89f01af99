// isomuscle: the command line. Subcommands live in one file each and register themselves
// (command_registry.hpp); this file only parses and turns errors into messages and exit codes.
#include <exception>
#include <iostream>

#include "app/command_registry.hpp"
#include "isomuscle/version.hpp"

namespace isomuscle::app {

std::vector<CommandInstaller>& command_installers() {
  static std::vector<CommandInstaller> installers;
  return installers;
}

namespace {
int g_exit_code = 0;
}
void set_exit_code(int code) {
  g_exit_code = code;
}
int exit_code() {
  return g_exit_code;
}

}  // namespace isomuscle::app

int main(int argc, char** argv) {
  using namespace isomuscle;
  CLI::App app{"isomuscle: active skeletal muscle on NURBS solids (isogeometric analysis)"};
  app.set_version_flag("--version", std::string("isomuscle ") + kVersion);
  app.require_subcommand(1);
  for (auto& install : app::command_installers())
    install(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    std::cerr << "isomuscle: error: " << e.what() << "\n";
    return 1;
  }
  return app::exit_code();
}
