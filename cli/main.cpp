// sylva: renders 3D plants as non-photorealistic illustrations. Bad input prints one line
// "sylva: error: <where>: <what>" and exits with status 2; nothing is written then.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <map>
#include <opencv2/core/utils/logger.hpp>
#include <string>

#include "cli/app.h"
#include "core/error.h"
#include "core/interrupt.h"

int main(int argc, char** argv) {
  // OpenCV's own log lines ("[ WARN:0@0.1] global ...") would break the one-line contract; its
  // failures reach sylva as exceptions and are reported from there.
  cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);
  sylva::install_interrupt_handlers();
  CLI::App app;
  const std::map<CLI::App*, sylva::cli::Action> actions = sylva::cli::add_commands(app);
  if (argc > 1 && argv[1][0] != '-') {
    std::string names;
    bool known = false;
    for (CLI::App* sub : app.get_subcommands({})) {
      known = known || sub->get_name() == argv[1];
      names += (names.empty() ? "" : ", ") + sub->get_name();
    }
    if (!known) {
      std::fprintf(stderr, "sylva: error: unknown command '%s' (commands: %s)\n", argv[1],
                   names.c_str());
      return 2;
    }
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
    std::string msg = e.what();
    for (char& c : msg)
      if (c == '\n') c = ' ';
    std::fprintf(stderr, "sylva: error: %s (see 'sylva --help')\n", msg.c_str());
    return 2;
  }
  try {
    for (CLI::App* sub : app.get_subcommands())
      actions.at(sub)();
  } catch (const sylva::InputError& e) {
    std::fprintf(stderr, "sylva: error: %s\n", e.what());
    return 2;
  } catch (const sylva::Interrupted& e) {
    std::fprintf(stderr, "sylva: %s; finished files are kept, nothing half-written\n", e.what());
    return 128 + e.signal();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sylva: failed: %s\n", e.what());
    return 1;
  }
  return 0;
}
