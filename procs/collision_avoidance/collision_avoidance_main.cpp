// collision_avoidance: chains of trajectory primitives to the next TARGETS, checked against
// the local obstacle map, sent as TRAJECTORY to the lld; reactive fallback when blocked.
#include "collision_avoidance/ca_node.h"
#include "runtime/process_main.h"

int main(int argc, char** argv)
{
  return rgnav::runtime::process_main(argc, argv, "collision_avoidance", [](rgnav::runtime::ProcessContext& ctx) {
    const auto options = rgnav::collision_avoidance::load_ca_options(ctx.config, ctx.robot);
    return std::make_shared<rgnav::collision_avoidance::CaNode>(ctx.node, options);
  });
}
