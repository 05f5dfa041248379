// tellus: the command-line front end of the Tellus terrain engine.
#include <vector>

#include <CLI/CLI.hpp>

#include "cli_support.hpp"
#include "tellus/core/logging.hpp"
#include "tellus/core/progress.hpp"

int main(int argc, char** argv) {
  CLI::App app{"Tellus: real-time rendering of very large terrains"};
  app.require_subcommand(1);
  bool verbose = false, quiet = false;
  app.add_flag("-v,--verbose", verbose, "Log debug messages (GL, GDAL)");
  app.add_flag("-q,--quiet", quiet, "Only log errors; no progress display");

  using namespace tellus::cli;
  const std::vector<Command> commands = {addInfoCommand(app), addRenderCommand(app),
                                         addGenerateCommand(app), addDemoCommand(app)};
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  tellus::initLogging(verbose ? spdlog::level::debug
                              : (quiet ? spdlog::level::err : spdlog::level::info));
  tellus::Progress::setEnabled(!quiet);
  for (const Command& command : commands) {
    if (command.app->parsed()) return command.run();
  }
  return 1;
}
