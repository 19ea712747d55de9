// sim_stereo_render: renders one stereo pair of the simulated head at a pose of a world and
// writes it as PNGs (left.png, right.png, depth as 16-bit millimetres left_depth.png, and a
// false-colour left_depth_view.png) for a person to look at; --repeat N renders N pairs and
// prints the rate (one core).
#include <CLI/CLI.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <chrono>
#include <ctime>
#include <filesystem>
#include <iostream>

#include "config/config.h"
#include "drivers/stereo/stereo_calibration.h"
#include "runtime/process_main.h"
#include "sim/stereo_renderer.h"
#include "sim/world_yaml.h"

int main(int argc, char** argv)
{
  using namespace rgnav;
  CLI::App app{"render one stereo pair of the simulated head"};
  std::string world_arg, out_dir = ".", calibration, worlds_dir;
  double x = 0, y = 0, theta = 0, pan = 0, tilt = 0, sigma = 2.0;
  int repeat = 0;
  app.add_option("world", world_arg, "world name (under --worlds-dir) or world file")->required();
  app.add_option("x", x, "robot x [m]")->required();
  app.add_option("y", y, "robot y [m]")->required();
  app.add_option("theta", theta, "robot heading [rad]")->required();
  app.add_option("--pan", pan, "head pan [rad], CCW +");
  app.add_option("--tilt", tilt, "head tilt [rad], + = up");
  app.add_option("--noise", sigma, "image noise sigma [grey levels]");
  app.add_option("--calibration", calibration, "calibration file (default: config/stereo/sim_b21r_head.yml)");
  app.add_option("--worlds-dir", worlds_dir, "where world names are looked up (default: config/worlds)");
  app.add_option("--out", out_dir, "folder for the PNGs");
  app.add_option("--repeat", repeat, "render this many pairs and print the rate");
  CLI11_PARSE(app, argc, argv);
  try {
    const std::string config_dir = runtime::default_config_dir();
    if (calibration.empty()) calibration = stereo::stereo_calibration_path(config_dir, "sim_b21r_head");
    if (worlds_dir.empty()) worlds_dir = config_dir + "/worlds";
    const sim::World world = sim::load_world(sim::resolve_world_path(world_arg, worlds_dir));
    sim::StereoRenderOptions options;
    options.noise_sigma = sigma;
    const sim::StereoRenderer renderer(world, stereo::load_stereo_calibration(calibration), options);
    sim::HeadView view;
    view.robot = {x, y, theta};
    view.pan = pan;
    view.tilt = tilt;
    for (const auto& p : world.people) view.people.push_back({p.path.front(), p.radius});
    sim::StereoRender r = renderer.render(view);
    std::filesystem::create_directories(out_dir);
    cv::Mat mm, view_depth;
    r.left.depth.convertTo(mm, CV_16U, 1000.0);
    cv::Mat scaled;
    r.left.depth.convertTo(scaled, CV_8U, 255.0 / 10.0);  // 0..10 m
    cv::applyColorMap(scaled, view_depth, cv::COLORMAP_JET);
    for (const auto& [name, image] : {std::pair<std::string, cv::Mat>{"left.png", r.left.image}, {"right.png", r.right.image},
                                      {"left_depth.png", mm}, {"left_depth_view.png", view_depth}})
      if (!cv::imwrite(out_dir + "/" + name, image)) throw std::runtime_error(out_dir + "/" + name + ": cannot write");
    std::cout << "wrote " << out_dir << "/{left,right,left_depth,left_depth_view}.png ("
              << world.name << ", " << renderer.faces().size() << " static faces)\n";
    if (repeat > 0) {
      // CPU time of this (single-threaded) process beside wall time: the machine may be shared.
      const std::clock_t c0 = std::clock();
      const auto t0 = std::chrono::steady_clock::now();
      for (int i = 0; i < repeat; ++i) {
        view.frame = static_cast<uint64_t>(i);
        view.robot.theta = theta + 0.01 * i;
        renderer.render(view, &r);  // into the same buffers, as stereo_capture does
      }
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      const double cpu = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
      std::cout << "rendered " << repeat << " stereo pairs: " << 1000.0 * cpu / repeat << " ms CPU per pair ("
                << repeat / cpu << " pairs/s on one core), " << 1000.0 * s / repeat << " ms wall per pair\n";
    }
    return 0;
  } catch (const config::ConfigError& e) {
    std::cerr << "sim_stereo_render: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "sim_stereo_render: " << e.what() << "\n";
    return 1;
  }
}
