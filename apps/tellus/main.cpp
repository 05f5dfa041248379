// tellus: the command-line front end of the Tellus terrain engine.
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli_support.hpp"
#include "tellus/core/logging.hpp"
#include "tellus/core/progress.hpp"

int main(int argc, char** argv) {
  CLI::App app{"Tellus: real-time rendering of very large terrains"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "tellus " TELLUS_VERSION);
  bool verbose = false, quiet = false;
  app.add_flag("-v,--verbose", verbose, "Log debug messages (GL, GDAL)");
  app.add_flag("-q,--quiet", quiet, "Only log errors; no progress display");

  using namespace tellus::cli;
  const std::vector<Command> commands = {
      addInfoCommand(app),   addRenderCommand(app), addGenerateCommand(app),
      addDemoCommand(app),   addBuildCommand(app),  addVerifyCommand(app),
      addExportCommand(app), addBenchCommand(app),  addViewCommand(app)};
  // A misspelt command gets a precise message rather than "a subcommand is required".
  if (argc > 1 && argv[1][0] != '-') {
    const bool known = std::any_of(commands.begin(), commands.end(),
                                   [&](const Command& c) { return c.app->get_name() == argv[1]; });
    if (!known) {
      std::string names;
      for (const Command& c : commands) names += (names.empty() ? "" : ", ") + c.app->get_name();
      std::fprintf(stderr, "tellus: unknown command '%s' (expected one of: %s)\n", argv[1],
                   names.c_str());
      return 2;
    }
  }
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
