// Message <-> plain conversions of the gateway detector (node adapter only); scans and poses
// convert with common/msg/conversions.h.
#pragma once

#include "gateway_detector/door_confirmation.h"
#include "gateway_detector/gateway_detector.h"
#include "rgnav/gateway_event_t.hpp"
#include "rgnav/gateway_hypotheses_t.hpp"
#include "rgnav/rectangle3d_t.hpp"

namespace rgnav::gateway_detector {

Rectangle3 to_rectangle(const rectangle3d_t& m);
int8_t to_class_msg(int output_class);
int from_class_msg(int8_t cls);
gateway_hypotheses_t to_hypotheses_msg(const DetectorOutput& out);
gateway_event_t to_event_msg(const GatewayEvent& e, int64_t utime, int64_t scan_id);

}  // namespace rgnav::gateway_detector
