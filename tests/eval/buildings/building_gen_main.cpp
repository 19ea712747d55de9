// rgnav_building_gen: random buildings for the benchmarks (building_layout.h), written in the
// IPA building maps' conventions: rand_<seed>.png, rand_<seed>_furnitures.png,
// rand_<seed>_gt_segmentation.png and rand_<seed>.json, for seeds S .. S+N-1. Prints each map's path.
#include <CLI/CLI.hpp>

#include <iostream>

#include "building_files.h"

int main(int argc, char** argv)
{
  CLI::App app{"write random buildings (IPA map triples with ground truth)"};
  uint64_t seed = 1;
  int count = 1;
  std::string out;
  app.add_option("--seed", seed, "seed of the first building")->required();
  app.add_option("--count", count, "buildings, seeds seed .. seed+count-1")->check(CLI::Range(1, 100000));
  app.add_option("--out", out, "output folder")->required();
  CLI11_PARSE(app, argc, argv);
  namespace rb = rgnav::buildings;
  try {
    for (int k = 0; k < count; ++k) {
      const auto building = rb::generate_building(seed + static_cast<uint64_t>(k));
      rb::write_building(building, rb::render_building(building), out);
      std::cout << out << "/" << rb::building_stem(building.seed) << ".png\n";
    }
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "rgnav_building_gen: " << e.what() << "\n";
    return 1;
  }
}
