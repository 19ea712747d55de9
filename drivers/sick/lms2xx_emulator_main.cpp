// lms2xx_emulator: an LMS 291 on a pseudo-terminal, scanning a synthetic room, for manual
// runs of laser_driver without hardware:
//   lms2xx_emulator --link /tmp/ttyLMS &
//   laser_driver --config config/laser_driver.yaml   (with laser_driver.port: /tmp/ttyLMS)
#include <CLI/CLI.hpp>
#include <signal.h>

#include <chrono>
#include <iostream>
#include <thread>

#include "lms2xx_emulator.h"
#include "synthetic_room.h"

int main(int argc, char** argv)
{
  using namespace rgnav::drivers::sick;
  CLI::App app{"SICK LMS 291 emulator on a pseudo-terminal"};
  EmulatorOptions options;
  SyntheticRoomOptions room;
  std::string units = "cm";
  app.add_option("--link", options.symlink_path, "stable symlink to the pty slave (e.g. /tmp/ttyLMS)");
  app.add_option("--baud", options.initial_baud, "power-on baud rate")->check(CLI::IsMember({9600, 19200, 38400, 500000}));
  app.add_option("--units", units, "power-on measuring units")->check(CLI::IsMember({"mm", "cm"}));
  app.add_option("--front", room.front_m, "distance to the front wall [m]");
  app.add_option("--left", room.left_m, "distance to the left wall [m]");
  app.add_option("--right", room.right_m, "distance to the right wall [m]");
  app.add_option("--back", room.back_m, "distance to the back wall [m]");
  app.add_option("--door-y-min", room.door_y_min_m, "doorway in the front wall from y [m]");
  app.add_option("--door-y-max", room.door_y_max_m, "doorway in the front wall to y [m]");
  CLI11_PARSE(app, argc, argv);
  options.units = units == "mm" ? Units::kMillimetres : Units::kCentimetres;

  // A shell starts background jobs with SIGINT ignored; sigwait() never sees an ignored
  // signal, so take the default disposition back before blocking.
  signal(SIGINT, SIG_DFL);
  signal(SIGTERM, SIG_DFL);
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &set, nullptr);  // before the device thread starts
  try {
    Lms2xxEmulator emulator(options, std::make_shared<SyntheticRoom>(room));
    std::cout << "LMS 291 emulator on " << emulator.port_path() << " at " << options.initial_baud << " baud"
              << std::endl;
    int sig = 0;
    sigwait(&set, &sig);
    const auto s = emulator.stats();
    std::cout << "stopping: " << s.requests << " requests, " << s.scans_sent << " scans sent, " << s.scans_skipped
              << " skipped" << std::endl;
  } catch (const std::exception& e) {
    std::cerr << "lms2xx_emulator: " << e.what() << std::endl;
    return 1;
  }
  return 0;
}
