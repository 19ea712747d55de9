// Message <-> plain conversions of the gateway detector (node adapter only).
#pragma once

#include "gateway_detector/door_confirmation.h"
#include "gateway_detector/gateway_detector.h"
#include "gateway_detector/scan.h"
#include "rgnav/gateway_event_t.hpp"
#include "rgnav/gateway_hypotheses_t.hpp"
#include "rgnav/laser_scan_t.hpp"
#include "rgnav/rectangle3d_t.hpp"

namespace rgnav::gateway_detector {

Scan to_scan(const laser_scan_t& m);
laser_scan_t to_laser_scan_msg(const Scan& s, const std::string& sensor);
Rectangle3 to_rectangle(const rectangle3d_t& m);
int8_t to_class_msg(int output_class);
int from_class_msg(int8_t cls);
gateway_hypotheses_t to_hypotheses_msg(const DetectorOutput& out);
gateway_event_t to_event_msg(const GatewayEvent& e, int64_t utime, int64_t scan_id);

}  // namespace rgnav::gateway_detector
