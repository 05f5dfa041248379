// tellus: the command-line front end of the Tellus terrain engine. Every command passes
// through here: its numbers are range-checked as they are parsed (cli_numbers.hpp), its files
// are checked before it runs (cli_files.hpp), and whatever it throws ends as one line on stderr
// and a non-zero exit rather than an abort. Exit codes: 0 done, 1 failed, 2 a usage error.
#include <algorithm>
#include <cstdio>
#include <exception>
#include <new>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli_files.hpp"
#include "cli_numbers.hpp"
#include "cli_support.hpp"
#include "stack_cli.hpp"
#include "tellus/core/logging.hpp"
#include "tellus/core/progress.hpp"
#include "tellus/tiles/http_byte_source.hpp"

int main(int argc, char** argv) {
  CLI::App app{"Tellus: real-time rendering of very large terrains"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "tellus " TELLUS_VERSION);
  bool verbose = false, quiet = false;
  app.add_flag("-v,--verbose", verbose, "Log debug messages (GL, GDAL)");
  app.add_flag("-q,--quiet", quiet, "Only log errors; no progress display");
  tellus::HttpSourceOptions http = tellus::HttpSourceOptions::processDefaults();
  double httpDeadlineS = double(http.deadlineMs) / 1000.0;
  app.add_option("--http-deadline", httpDeadlineS,
                 "Stores over http(s)://: seconds a read may take, retries included, before the "
                 "command fails (default 25; a URL that failed is not asked again for 30 s)")
      ->check(tellus::cli::numberIn(0.1, 86400.0));
  app.add_option("--http-retries", http.retries,
                 "Stores over http(s)://: retries of a failed read within its deadline (default 3)")
      ->check(tellus::cli::integerIn(0, 100));

  using namespace tellus::cli;
  const std::vector<Command> commands = {
      addInfoCommand(app),   addRenderCommand(app), addGenerateCommand(app),
      addDemoCommand(app),   addBuildCommand(app),  addVerifyCommand(app),
      addExportCommand(app), addBenchCommand(app),  addViewCommand(app),
      addStacksCommand(app), addRenderersCommand(app)};
  requireFiniteNumbers(app);
  refuseEmptyValues(app);
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
    // --help and --version exit 0; every usage error (a missing argument, a value out of
    // range, an unknown option) exits 2, as an unknown command does, whatever CLI11's own code.
    return app.exit(e) == 0 ? 0 : 2;
  }
  tellus::initLogging(verbose ? spdlog::level::debug
                              : (quiet ? spdlog::level::err : spdlog::level::info));
  tellus::Progress::setEnabled(!quiet);
  http.deadlineMs = long(httpDeadlineS * 1000.0);
  tellus::HttpSourceOptions::setProcessDefaults(http);
  for (const Command& command : commands) {
    if (!command.app->parsed()) continue;
    std::string inputs;  // for the last-resort messages
    try {
      if (command.files) {
        const CommandFiles files = command.files();
        for (const std::string& input : files.inputs) inputs += (inputs.empty() ? "'" : ", '") + input + "'";
        if (tellus::Status checked = checkCommandFiles(files); !checked) return fail(checked.error());
      }
      return command.run();
    } catch (const std::bad_alloc&) {
      // The commands estimate their memory before allocating (memory_budget.hpp); this is the
      // last resort when an estimate was wrong.
      std::fprintf(stderr, "tellus %s: out of memory%s%s (an allocation no estimate foresaw; "
                   "TELLUS_MEMORY_LIMIT_MB lowers what Tellus tries)\n",
                   command.app->get_name().c_str(), inputs.empty() ? "" : " reading ", inputs.c_str());
    } catch (const std::exception& e) {
      std::fprintf(stderr, "tellus %s: internal error: %s\n", command.app->get_name().c_str(),
                   e.what());
    }
    return 1;
  }
  return 1;
}
