// stereo_capture: publishes STEREO_IMAGES from two cameras or a folder of recorded pairs.
#include "drivers/stereo/stereo_capture_node.h"
#include "runtime/process_main.h"

int main(int argc, char** argv)
{
  using namespace rgnav;
  return runtime::process_main(argc, argv, "stereo_capture", [](runtime::ProcessContext& ctx) {
    auto options = stereo::load_capture_options(ctx.config.section("capture"), ctx.config.section("channels"),
                                                runtime::default_data_dir());
    return std::make_shared<stereo::StereoCaptureNode>(ctx.node, options, stereo::make_source(options));
  });
}
