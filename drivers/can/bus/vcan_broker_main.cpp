// vcan_broker: serves one user-space virtual CAN bus until SIGINT/SIGTERM.
//   vcan_broker --bus base            # /tmp/rgnav-vcan-base.sock
//   vcan_broker --path @rgnav-test    # abstract namespace
#include <CLI/CLI.hpp>

#include <csignal>
#include <cstdio>

#include "bus/can_interface.h"
#include "bus/vcan_broker.h"
#include "bus/vcan_protocol.h"
#include "log/log.h"
#include "runtime/realtime.h"

namespace {
volatile std::sig_atomic_t g_stop = 0;
void on_signal(int) { g_stop = 1; }
}  // namespace

int main(int argc, char** argv)
{
  CLI::App app{"user-space virtual CAN bus broker"};
  std::string bus = "base";
  std::string path;
  std::string log_level = "info";
  int realtime_priority = 0;
  app.add_option("--bus", bus, "bus name: socket /tmp/rgnav-vcan-<bus>.sock");
  app.add_option("--path", path, "socket path (overrides --bus); '@name' = abstract namespace");
  app.add_option("--log-level", log_level, "trace|debug|info|warn|error");
  app.add_option("--realtime-priority", realtime_priority,
                 "SCHED_FIFO priority when permitted (0: normal); a starved broker holds back every frame at once")
      ->check(CLI::Range(0, 99));
  CLI11_PARSE(app, argc, argv);
  try {
    rgnav::log::init("vcan_broker", log_level);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vcan_broker: %s\n", e.what());
    return 2;
  }
  if (path.empty()) path = rgnav::can::vcan::default_socket_path(bus);
  struct sigaction sa{};
  sa.sa_handler = on_signal;
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
  try {
    rgnav::can::VcanBroker broker(path);
    spdlog::info("serving virtual CAN bus on {}", path);
    if (realtime_priority > 0)
      rgnav::runtime::request_realtime_logged("virtual CAN bus thread", realtime_priority, false,
                                              "frames may stall under load");
    while (!g_stop) broker.run_once(std::chrono::milliseconds(200));
    const auto s = broker.stats();
    spdlog::info("stopped: {} frames in, {} deliveries, {} dropped by hooks, {} overflow drops", s.frames_in,
                 s.deliveries, s.dropped_by_hook, s.overflow_drops);
    return 0;
  } catch (const rgnav::can::CanError& e) {
    spdlog::critical("{}", e.what());
    return 1;
  }
}
