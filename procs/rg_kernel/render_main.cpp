// rgnav_render: pictures and global map exports of an rgmap.json (./rgnav render).
#include <CLI/CLI.hpp>

#include <iostream>

#include "render/rgmap_picture.h"
#include "rgmap/saved_map.h"

int main(int argc, char** argv)
{
  using namespace rgnav;
  CLI::App app{"Render an RG map (rgmap.json) as SVG/PNG, or export it as a map_server PGM + YAML"};
  std::string in;
  std::vector<std::string> outs;
  std::string export_base;
  double ppm = 40, resolution = 0.05;
  app.add_option("rgmap", in, "rgmap.json (as written by rg_kernel or ./rgnav map), or a folder holding one")->required();
  app.add_option("--out", outs, "picture(s) to write: .svg or .png");
  app.add_option("--export-pgm", export_base, "write <base>.pgm + <base>.yaml (global metric map)");
  app.add_option("--pixels-per-metre", ppm, "picture scale")->check(CLI::Range(1.0, 500.0));
  app.add_option("--resolution", resolution, "export cell size [m]")->check(CLI::Range(0.01, 1.0));
  CLI11_PARSE(app, argc, argv);
  if (outs.empty() && export_base.empty()) {
    std::cerr << "nothing to do: give --out and/or --export-pgm\n";
    return 2;
  }
  try {
    // Every defect is named with the file (damaged framing, not JSON, not an RG map), and
    // nothing is written for a map that did not load.
    const rgmap::RgMap map = rgmap::load_saved_map(in);
    for (const auto& o : outs) {
      render::render_rgmap(map, o, ppm);
      std::cout << "wrote " << o << "\n";
    }
    if (!export_base.empty()) {
      render::write_map_server(render::compose_global_grid(map, resolution), export_base);
      std::cout << "wrote " << export_base << ".pgm and " << export_base << ".yaml\n";
    }
  } catch (const std::exception& e) {
    std::cerr << "rgnav render: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
