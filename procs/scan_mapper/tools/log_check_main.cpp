// rgnav_log_check: is each file an LCM log, and is it whole? Run by ./rgnav replay before it
// starts the stack, so that a file that is no log is refused instead of replaying nothing.
//   rgnav_log_check LOG [LOG...]
// Prints "LOG: N events" per file, and a warning naming the file when one is cut off or damaged
// (it is then replayed up to the damage). Exit 0 when every file is a log, 1 when one is not
// (missing, empty, no LCM event at its start), 2 on bad usage.
#include <CLI/CLI.hpp>

#include <iostream>

#include "importers/lcm_log_io.h"

int main(int argc, char** argv)
{
  CLI::App app{"Check that files are LCM logs (framing only, nothing is decoded)"};
  std::vector<std::string> logs;
  app.add_option("logs", logs, "LCM log files")->required();
  CLI11_PARSE(app, argc, argv);
  int status = 0;
  for (const auto& path : logs) {
    try {
      const auto f = rgnav::importers::for_each_lcm_event(path, [](const lcm::LogEvent&, int64_t) {});
      std::cout << path << ": " << f.events << " events\n";
      for (const auto& i : f.issues) std::cerr << path << ": warning: event " << i.line << ": " << i.what << "\n";
    } catch (const std::exception& e) {
      std::cerr << "rgnav_log_check: " << e.what() << "\n";
      status = 1;
    }
  }
  return status;
}
