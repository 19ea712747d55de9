// rgnav_name_region: the operator names a region (./rgnav name-region ID NAME). Publishes one
// region_name_t on REGION_NAME: the RG kernel writes the name into its map (journaled, as any
// change), a running planner takes goals by it at once. With --map, the name is also written
// into that saved map (rgmap.json, atomically), for a robot that runs on a saved map with no RG
// kernel; the name is checked against it first (the region must be there, the name no other
// region's), and nothing is sent or written when it is refused.
//   rgnav_name_region ID NAME [--map rgmap.json|DIR]
// Exit codes: 0 sent (and written), 2 refused (bad name, unknown region), 1 a bus or file failure.
#include <CLI/CLI.hpp>

#include <iostream>
#include <string>

#include "bus/lcm_bus.h"
#include "bus/typed.h"
#include "rgmap/region_name.h"
#include "rgmap/rg_map.h"
#include "rgmap/saved_map.h"
#include "rgnav/region_name_t.hpp"
#include "time/message_time.h"

int main(int argc, char** argv)
{
  CLI::App app{"Name a region of the RG map (for goals by name: ./rgnav goto NAME).\n"
               "Exit codes: 0 sent (and written with --map), 2 refused, 1 a bus or file failure."};
  int64_t region = 0;
  std::string name, map_path, url, channel = "REGION_NAME";
  app.add_option("id", region, "the region's id")->required()->check(CLI::Range(int64_t{1}, int64_t{1} << 62));
  app.add_option("name", name, "its name: 1-64 printable ASCII characters, not only digits")->required();
  app.add_option("--map", map_path, "also write the name into this saved map (rgmap.json or its folder)");
  app.add_option("--lcm-url", url, "LCM URL (default: LCM_DEFAULT_URL or LCM's default)");
  app.add_option("--channel", channel, "the channel the RG kernel and the planner read (channels.region_name)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;   // --help is 0; anything CLI11 refuses is a bad argument
  }
  std::string why;
  if (!rgnav::rgmap::valid_region_name(name, &why)) {
    std::cerr << "rgnav name-region: " << why << "\n";
    return 2;
  }

  if (!map_path.empty()) {
    const std::string file = rgnav::rgmap::saved_map_file(map_path);
    try {
      rgnav::rgmap::RgMap map = rgnav::rgmap::load_saved_map(map_path);
      const int64_t live = rgnav::rgmap::region_to_name(map, region, name, &why);
      if (live == 0) {
        std::cerr << "rgnav name-region: " << file << ": " << why << "\n";
        return 2;
      }
      rgnav::rgmap::Region* r = map.region(live);
      if (r->name != name) {
        r->name = name;
        ++map.version;   // a changed map is a new version, as the kernel counts them
        rgnav::rgmap::save_map(map, map_path);
      }
      std::cout << "wrote " << file << ": region " << live << " is '" << name << "'\n";
    } catch (const std::exception& e) {
      std::cerr << "rgnav name-region: " << e.what() << "\n";
      return 1;
    }
  }

  rgnav::region_name_t m;
  m.utime = rgnav::time::wall_utime();
  m.region_id = region;
  m.name = name;
  try {
    rgnav::bus::LcmBus bus(url);
    if (!rgnav::bus::publish(bus, channel, m)) {
      std::cerr << "rgnav name-region: name refused (see the message above)\n";
      return 2;
    }
  } catch (const std::exception& e) {
    std::cerr << "rgnav name-region: " << e.what() << "\n";
    return 1;
  }
  std::cout << "sent on " << channel << ": region " << region << " is '" << name << "'\n";
  return 0;
}
