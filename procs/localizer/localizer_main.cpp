// localizer: region-based Monte Carlo localization in the RG map. LASER_FRONT + ODOMETRY and
// the map (RG_MAP, or a saved map with --map) -> POSE, LOCALIZER_GATEWAY_PASSED.
//   localizer [--config config/localizer.yaml] [--map rgmap.json|DIR] [--state-file PATH]
#include <CLI/CLI.hpp>

#include "localizer/localizer_node.h"
#include "localizer/localizer_options.h"
#include "runtime/process_main.h"

namespace loc = rgnav::localizer;

int main(int argc, char** argv)
{
  loc::LocalizerFiles files;
  return rgnav::runtime::process_main(
      argc, argv, "localizer",
      [&](rgnav::runtime::ProcessContext& ctx) {
        const auto options = loc::load_localizer_options(ctx.config, ctx.robot);
        // --check-config reads no map and neither reads nor writes the saved estimate.
        if (ctx.checking_only) files = {};
        return std::make_shared<loc::LocalizerNode>(ctx.node, options, files);
      },
      [&](CLI::App& app) {
        app.add_option("--map", files.map, "saved RG map to localize in: rgmap.json or a folder holding one (else RG_MAP)");
        app.add_option("--state-file", files.state_file, "where the estimate is saved and resumed from");
      });
}
