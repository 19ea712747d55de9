// Loading and validating the RG kernel's options from config/rg_kernel.yaml (sections kernel,
// line_map, freespace, objects, doorways and graph; every value range-checked). The rg_kernel
// process and the offline pipeline both load them here, so they never disagree about a
// parameter; unknown keys are refused by Config::finish.
#pragma once

#include "config/config.h"
#include "config/robot_description.h"
#include "procs/rg_kernel/rg_kernel.h"
#include "rgmap/rg_graph.h"

namespace rgnav::rg_kernel {

// Reads sections kernel, line_map, freespace, objects and doorways of `cfg`; the cells under the
// robot at each scan are free, within the robot description's radius.
KernelOptions load_kernel_options(const config::Config& cfg, const config::RobotDescription& robot);
ObjectOptions load_object_options(const config::Config& objects_section);
rgmap::GraphOptions load_graph_options(const config::Config& graph_section);

}  // namespace rgnav::rg_kernel
