// viewer: the live view of the robot in a browser. The map, pose, scan, plan and status
// channels -> a page and a WebSocket stream on http://ADDRESS:PORT/ (config/viewer.yaml; loopback
// by default); NAV_GOAL for a region clicked on the page.
//   viewer [--config config/viewer.yaml] [--address IP] [--port N]
#include <CLI/CLI.hpp>

#include <iostream>

#include "runtime/process_main.h"
#include "viewer/viewer_node.h"

namespace vw = rgnav::viewer;

int main(int argc, char** argv)
{
  std::string address;
  int port = -1;
  return rgnav::runtime::process_main(
      argc, argv, "viewer",
      [&](rgnav::runtime::ProcessContext& ctx) {
        auto options = vw::load_viewer_options(ctx.config, ctx.robot, RGNAV_VIEWER_WEB_ROOT);
        if (!address.empty()) options.server.address = address;
        if (port >= 0) options.server.port = static_cast<uint16_t>(port);
        auto node = std::make_shared<vw::ViewerNode>(ctx.node, options, ctx.robot.laser_front.base_from_laser, !ctx.checking_only);
        // On stdout too, for the scripts that start it (./rgnav view, demo) with --port 0.
        if (!ctx.checking_only) std::cout << "viewer: http://" << options.server.address << ":" << node->port() << "/" << std::endl;
        return node;
      },
      [&](CLI::App& app) {
        app.add_option("--address", address, "listen address (overrides http.address)");
        app.add_option("--port", port, "listen port, 0 = any free one (overrides http.port)")->check(CLI::Range(0, 65535));
      });
}
