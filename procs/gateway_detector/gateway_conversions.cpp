#include "gateway_detector/gateway_conversions.h"

#include <cmath>

#include "msg/conversions.h"

namespace rgnav::gateway_detector {

namespace {
using H = gateway_hypothesis_t;
// Output classes and the message constants, pair by pair (no reliance on equal numbering).
const int8_t kClassMsg[kNumOutputClasses] = {
    H::CLASS_UNKNOWN,    H::CLASS_DOOR,        H::CLASS_NARROW_PASSAGE, H::CLASS_X_CROSSING,
    H::CLASS_T_CROSSING, H::CLASS_LT_CROSSING, H::CLASS_RT_CROSSING,    H::CLASS_L_TURN,
    H::CLASS_R_TURN,     H::CLASS_DEAD_END,    H::CLASS_HALLWAY,        H::CLASS_OPENING};
static_assert(H::NUM_CLASSES == kNumOutputClasses, "gateway class lists differ");

void fill_probabilities(const OutputProbabilities& p, float* out)
{
  for (int c = 0; c < kNumOutputClasses; ++c) out[c] = 0.f;
  double sum = 0.0;
  for (double x : p) sum += x;
  for (int c = 0; c < kNumOutputClasses; ++c)
    out[kClassMsg[c]] = sum > 0 ? static_cast<float>(p[static_cast<size_t>(c)] / sum) : (c == kOutUnknown ? 1.f : 0.f);
}
}  // namespace

Rectangle3 to_rectangle(const rectangle3d_t& m)
{
  Rectangle3 r;
  for (int i = 0; i < 4; ++i) r.corners[static_cast<size_t>(i)] = {m.corners[i][0], m.corners[i][1], m.corners[i][2]};
  r.normal = {m.normal[0], m.normal[1], m.normal[2]};
  r.width = m.width;
  r.height = m.height;
  return r;
}

int8_t to_class_msg(int c) { return c >= 0 && c < kNumOutputClasses ? kClassMsg[c] : H::CLASS_UNKNOWN; }

int from_class_msg(int8_t cls)
{
  for (int c = 0; c < kNumOutputClasses; ++c)
    if (kClassMsg[c] == cls) return c;
  return kOutUnknown;
}

gateway_hypotheses_t to_hypotheses_msg(const DetectorOutput& out)
{
  gateway_hypotheses_t m;
  m.utime = out.utime;
  m.scan_id = out.scan_id;
  m.map_from_base = msg::to_msg(out.map_from_base);
  for (const auto& h : out.hypotheses) {
    gateway_hypothesis_t g;
    g.track_id = h.track_id;
    g.gateway_class = to_class_msg(h.gateway_class);
    fill_probabilities(h.probabilities, g.class_probability);
    for (const auto& p : h.gateway_points) g.gateway_points.push_back(msg::to_point_msg(p));
    g.npoints = static_cast<int32_t>(g.gateway_points.size());
    for (const auto& p : h.crossing_points) g.crossing_points.push_back(msg::to_point_msg(p));
    g.ncrossing_points = static_cast<int32_t>(g.crossing_points.size());
    g.traversal_directions = h.traversal_directions;
    g.ndirections = static_cast<int32_t>(g.traversal_directions.size());
    g.distance = static_cast<float>(std::isfinite(h.distance) ? h.distance : 0.0);
    g.observations = h.observations;
    m.hypotheses.push_back(std::move(g));
  }
  m.nhypotheses = static_cast<int32_t>(m.hypotheses.size());
  return m;
}

gateway_event_t to_event_msg(const GatewayEvent& e, int64_t utime, int64_t scan_id)
{
  gateway_event_t m;
  m.utime = utime;
  m.scan_id = scan_id;
  switch (e.kind) {
    case EventKind::kApproached: m.event = gateway_event_t::EVENT_APPROACHED; break;
    case EventKind::kEntered: m.event = gateway_event_t::EVENT_ENTERED; break;
    case EventKind::kTraversed: m.event = gateway_event_t::EVENT_TRAVERSED; break;
    case EventKind::kLost: m.event = gateway_event_t::EVENT_LOST; break;
  }
  m.track_id = e.track_id;
  m.gateway_class = to_class_msg(e.gateway_class);
  fill_probabilities(e.probabilities, m.class_probability);
  m.map_from_base = msg::to_msg(e.map_from_base);
  for (const auto& p : e.gateway_points) m.gateway_points.push_back(msg::to_point_msg(p));
  m.npoints = static_cast<int32_t>(m.gateway_points.size());
  m.direction = geometry::normalize_angle(e.direction);
  return m;
}

}  // namespace rgnav::gateway_detector
