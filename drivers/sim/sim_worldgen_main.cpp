// sim_worldgen: writes the built-in worlds (world_generator.h) as YAML into a directory
// (config/worlds/ in the repository). Deterministic: running it twice gives the same bytes.
#include <CLI/CLI.hpp>

#include <filesystem>
#include <fstream>
#include <iostream>

#include "sim/world_generator.h"
#include "sim/world_yaml.h"

int main(int argc, char** argv)
{
  CLI::App app{"write the built-in rgnav worlds"};
  std::string dir;
  app.add_option("dir", dir, "output directory")->required();
  CLI11_PARSE(app, argc, argv);
  std::filesystem::create_directories(dir);
  for (const auto& [name, world] : rgnav::sim::builtin_worlds()) {
    const std::string path = dir + "/" + name + ".yaml";
    std::ofstream out(path);
    if (!(out << rgnav::sim::world_to_yaml(world))) {
      std::cerr << path << ": cannot write\n";
      return 1;
    }
    std::cout << path << "\n";
  }
  return 0;
}
