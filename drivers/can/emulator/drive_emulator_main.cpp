// drive_emulator: the two emulated CiA 402 drives of the B21r synchro drive (translation and
// rotation), each its own client of a virtual CAN bus (or a SocketCAN interface), for manual
// runs and process tests. Runs until SIGINT/SIGTERM.
//   drive_emulator --bus base --translation-node 2 --rotation-node 3
#include <CLI/CLI.hpp>

#include <csignal>
#include <cstdio>

#include "bus/socket_can.h"
#include "bus/vcan_protocol.h"
#include "bus/virtual_can.h"
#include "emulator/emulator_runner.h"
#include "log/log.h"

namespace {
volatile std::sig_atomic_t g_stop = 0;
void on_signal(int) { g_stop = 1; }
}  // namespace

int main(int argc, char** argv)
{
  using namespace rgnav::can;
  CLI::App app{"emulated CiA 402 drives (translation + rotation) on a CAN bus"};
  std::string bus = "base";
  std::string path;
  std::string socketcan;
  int translation_node = 2;
  int rotation_node = 3;
  std::string log_level = "info";
  app.add_option("--bus", bus, "virtual bus name: socket /tmp/rgnav-vcan-<bus>.sock");
  app.add_option("--path", path, "virtual bus socket path (overrides --bus)");
  app.add_option("--socketcan", socketcan, "use this SocketCAN interface instead of the virtual bus");
  app.add_option("--translation-node", translation_node, "node id of the translation drive")->check(CLI::Range(1, 127));
  app.add_option("--rotation-node", rotation_node, "node id of the rotation drive")->check(CLI::Range(1, 127));
  app.add_option("--log-level", log_level, "trace|debug|info|warn|error");
  CLI11_PARSE(app, argc, argv);
  try {
    rgnav::log::init("drive_emulator", log_level);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "drive_emulator: %s\n", e.what());
    return 2;
  }
  if (translation_node == rotation_node) {
    spdlog::critical("translation and rotation node ids must differ");
    return 2;
  }
  if (path.empty()) path = vcan::default_socket_path(bus);
  struct sigaction sa{};
  sa.sa_handler = on_signal;
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
  try {
    emulator::EmulatorRunner runner;
    for (int node : {translation_node, rotation_node}) {
      std::unique_ptr<CanInterface> iface;
      if (!socketcan.empty()) {
        iface = std::make_unique<SocketCan>(socketcan);
      } else {
        VirtualCanOptions o;
        o.path = path;
        o.client_name = "drive-" + std::to_string(node);
        o.connect_timeout = std::chrono::milliseconds(5000);
        o.reconnect_interval = std::chrono::milliseconds(200);
        iface = std::make_unique<VirtualCan>(o);
      }
      emulator::DriveEmulatorOptions d;
      d.node_id = static_cast<uint8_t>(node);
      runner.add(std::move(iface), d);
    }
    runner.power_on(std::chrono::steady_clock::now());
    spdlog::info("drives {} (translation) and {} (rotation) on {}", translation_node, rotation_node,
                 socketcan.empty() ? path : socketcan);
    while (!g_stop) runner.run_once(std::chrono::milliseconds(1));
    spdlog::info("stopped ({} frames could not be sent)", runner.send_failures());
    return 0;
  } catch (const CanError& e) {
    spdlog::critical("{}", e.what());
    return 1;
  }
}
