// Paths into the source tree for tests whose target defines RGNAV_SOURCE_DIR.
#pragma once

#include <string>

namespace rgnav::testing {

#ifdef RGNAV_SOURCE_DIR
// <source tree>/config/<name>: a shipped config file.
inline std::string config_path(const std::string& name) { return std::string(RGNAV_SOURCE_DIR) + "/config/" + name; }
#endif

}  // namespace rgnav::testing
