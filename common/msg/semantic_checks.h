// Checks beyond the wire format (which the generated validators already enforce: lengths,
// finite floats, enums): values a well-formed message of each type must also satisfy.
// Used on every received message (bus/typed.h) and before publishing.
#pragma once

#include <string>

#include "rgnav_validators.hpp"

namespace rgnav::msg {

// Generic: nothing beyond the wire checks.
template <class T>
bool semantically_valid(const T&, std::string*)
{
  return true;
}

bool semantically_valid(const laser_scan_t& m, std::string* why);
bool semantically_valid(const odometry_t& m, std::string* why);
bool semantically_valid(const velocity_cmd_t& m, std::string* why);
bool semantically_valid(const image_t& m, std::string* why);
bool semantically_valid(const stereo_images_t& m, std::string* why);
bool semantically_valid(const obstacle_grid_t& m, std::string* why);
bool semantically_valid(const region_t& m, std::string* why);
bool semantically_valid(const trajectory_t& m, std::string* why);
bool semantically_valid(const nav_goal_t& m, std::string* why);
bool semantically_valid(const target_list_t& m, std::string* why);
bool semantically_valid(const aligned_scan_t& m, std::string* why);
bool semantically_valid(const localize_request_t& m, std::string* why);
bool semantically_valid(const gateway_passed_t& m, std::string* why);
bool semantically_valid(const region_name_t& m, std::string* why);
bool semantically_valid(const ca_status_t& m, std::string* why);
bool semantically_valid(const global_path_t& m, std::string* why);
bool semantically_valid(const region_name_request_t& m, std::string* why);
bool semantically_valid(const explorer_status_t& m, std::string* why);

}  // namespace rgnav::msg
