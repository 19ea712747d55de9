#include "sim/world.h"

#include <cmath>

namespace rgnav::sim {

namespace {

struct KindName { RegionKind kind; const char* name; };
constexpr KindName kKinds[] = {
    {RegionKind::kRoom, "room"}, {RegionKind::kHallway, "hallway"},
    {RegionKind::kLobby, "lobby"}, {RegionKind::kOther, "other"}};

struct ClassName { GatewayClass cls; const char* name; };
constexpr ClassName kClasses[] = {
    {GatewayClass::kDoor, "door"}, {GatewayClass::kNarrowPassage, "narrow_passage"},
    {GatewayClass::kXCrossing, "x_crossing"}, {GatewayClass::kTJunction, "t_junction"},
    {GatewayClass::kLTJunction, "lt_junction"}, {GatewayClass::kRTJunction, "rt_junction"},
    {GatewayClass::kLTurn, "l_turn"}, {GatewayClass::kRTurn, "r_turn"},
    {GatewayClass::kOpening, "opening"}, {GatewayClass::kDeadEnd, "dead_end"}};

}  // namespace

bool Door::open_at(double t) const
{
  bool state = open;
  for (const auto& e : schedule) {
    if (e.t > t) break;
    state = e.open;
  }
  return state;
}

Vec2 rotate(const Vec2& v, double angle)
{
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}

double normalize_angle(double a)
{
  a = std::remainder(a, 2.0 * M_PI);  // [-pi, pi]
  if (a <= -M_PI) a += 2.0 * M_PI;
  return a;
}

std::vector<Vec2> Box::corners() const
{
  const Vec2 h = size / 2.0;
  return {center + rotate({-h.x(), -h.y()}, yaw), center + rotate({h.x(), -h.y()}, yaw),
          center + rotate({h.x(), h.y()}, yaw), center + rotate({-h.x(), h.y()}, yaw)};
}

std::vector<Box> Table::parts() const
{
  std::vector<Box> out;
  const Vec2 inset = size / 2.0 - Vec2(leg_size, leg_size);
  const Vec2 signs[4] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  for (int i = 0; i < 4; ++i) {
    Box leg;
    leg.name = name + ".leg" + std::to_string(i);
    leg.center = center + rotate(inset.cwiseProduct(signs[i]), yaw);
    leg.size = {leg_size, leg_size};
    leg.yaw = yaw;
    leg.z_min = 0.0;
    leg.z_max = height - top_thickness;
    out.push_back(leg);
  }
  Box top;
  top.name = name + ".top";
  top.center = center;
  top.size = size;
  top.yaw = yaw;
  top.z_min = height - top_thickness;
  top.z_max = height;
  out.push_back(top);
  return out;
}

const char* to_string(RegionKind k)
{
  for (const auto& e : kKinds)
    if (e.kind == k) return e.name;
  return "other";
}

const char* to_string(GatewayClass c)
{
  for (const auto& e : kClasses)
    if (e.cls == c) return e.name;
  return "door";
}

std::optional<RegionKind> region_kind_from_string(const std::string& s)
{
  for (const auto& e : kKinds)
    if (s == e.name) return e.kind;
  return std::nullopt;
}

std::optional<GatewayClass> gateway_class_from_string(const std::string& s)
{
  for (const auto& e : kClasses)
    if (s == e.name) return e.cls;
  return std::nullopt;
}

std::vector<std::string> region_kind_names()
{
  std::vector<std::string> out;
  for (const auto& e : kKinds) out.push_back(e.name);
  return out;
}

std::vector<std::string> gateway_class_names()
{
  std::vector<std::string> out;
  for (const auto& e : kClasses) out.push_back(e.name);
  return out;
}

bool point_in_polygon(const Vec2& p, const std::vector<Vec2>& poly)
{
  bool inside = false;
  const size_t n = poly.size();
  for (size_t i = 0, j = n - 1; i < n; j = i++) {
    const Vec2& a = poly[i];
    const Vec2& b = poly[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
      inside = !inside;
  }
  return inside;
}

double polygon_area(const std::vector<Vec2>& poly)
{
  double a = 0.0;
  const size_t n = poly.size();
  for (size_t i = 0, j = n - 1; i < n; j = i++) a += poly[j].x() * poly[i].y() - poly[i].x() * poly[j].y();
  return std::fabs(a) / 2.0;
}

}  // namespace rgnav::sim
