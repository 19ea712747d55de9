#include "rgmap/rg_map.h"

#include <cmath>
#include <stdexcept>

#include "rgmap/region_name.h"

namespace rgnav::rgmap {

std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> gateway_edges(const std::vector<Eigen::Vector2d>& points)
{
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> edges;
  if (points.size() == 4) {
    for (size_t k = 0; k < 4; ++k) edges.emplace_back(points[k], points[(k + 1) % 4]);
    return edges;
  }
  for (size_t k = 0; k + 1 < points.size(); k += 2) edges.emplace_back(points[k], points[k + 1]);
  return edges;
}

const char* to_string(GatewayClass c)
{
  switch (c) {
    case GatewayClass::kUnknown: return "unknown";
    case GatewayClass::kDoor: return "door";
    case GatewayClass::kNarrowPassage: return "narrow passage";
    case GatewayClass::kXCrossing: return "X-crossing";
    case GatewayClass::kTCrossing: return "T-junction";
    case GatewayClass::kLTCrossing: return "LT-junction";
    case GatewayClass::kRTCrossing: return "RT-junction";
    case GatewayClass::kLTurn: return "L-turn";
    case GatewayClass::kRTurn: return "R-turn";
    case GatewayClass::kDeadEnd: return "dead end";
    case GatewayClass::kHallway: return "hallway";
    case GatewayClass::kOpening: return "opening";
  }
  return "invalid";
}

Region& RgMap::add_region(const geometry::Pose2& map_from_region, int64_t t)
{
  const int64_t id = next_region_id_++;
  Region& r = regions_[id];
  r.id = id;
  r.map_from_region = map_from_region;
  r.utime = t;
  ++version;
  return r;
}

Gateway& RgMap::add_gateway(GatewayClass cls, int64_t region_a, int64_t t)
{
  if (!region(region_a)) throw std::invalid_argument("add_gateway: unknown region " + std::to_string(region_a));
  const int64_t id = next_gateway_id_++;
  Gateway& g = gateways_[id];
  g.id = id;
  g.cls = cls;
  g.region_a = region_a;
  utime = std::max(utime, t);
  ++version;
  return g;
}

Region& RgMap::insert_region(Region r)
{
  if (r.id <= 0 || regions_.count(r.id)) throw std::invalid_argument("region id " + std::to_string(r.id) + " invalid or duplicate");
  next_region_id_ = std::max(next_region_id_, r.id + 1);
  const int64_t id = r.id;
  return regions_[id] = std::move(r);
}

Gateway& RgMap::insert_gateway(Gateway g)
{
  if (g.id <= 0 || gateways_.count(g.id)) throw std::invalid_argument("gateway id " + std::to_string(g.id) + " invalid or duplicate");
  next_gateway_id_ = std::max(next_gateway_id_, g.id + 1);
  const int64_t id = g.id;
  return gateways_[id] = std::move(g);
}

Region* RgMap::region(int64_t id)
{
  auto it = regions_.find(id);
  return it == regions_.end() ? nullptr : &it->second;
}
const Region* RgMap::region(int64_t id) const
{
  auto it = regions_.find(id);
  return it == regions_.end() ? nullptr : &it->second;
}
Gateway* RgMap::gateway(int64_t id)
{
  auto it = gateways_.find(id);
  return it == gateways_.end() ? nullptr : &it->second;
}
const Gateway* RgMap::gateway(int64_t id) const
{
  auto it = gateways_.find(id);
  return it == gateways_.end() ? nullptr : &it->second;
}

int64_t RgMap::resolve(int64_t id) const
{
  // Merge chains are short; the bound guards against a corrupt cycle.
  for (size_t hops = 0; hops <= regions_.size(); ++hops) {
    const Region* r = region(id);
    if (!r || r->state != Region::State::kMerged) return id;
    id = r->merged_into;
  }
  return 0;
}

void RgMap::connect(int64_t gateway_id, int64_t region_b, const geometry::Pose2& a_from_b)
{
  Gateway* g = gateway(gateway_id);
  if (!g || !region(region_b)) throw std::invalid_argument("connect: unknown gateway or region");
  g->region_b = region_b;
  g->region_a_from_region_b = a_from_b;
  g->neutralized = resolve(g->region_a) == resolve(region_b);
  ++version;
}

Rectangle3d moved(Rectangle3d r, const geometry::Pose2& to_from)
{
  const double c = std::cos(to_from.theta()), s = std::sin(to_from.theta());
  Eigen::Matrix3d rot;
  rot << c, -s, 0, s, c, 0, 0, 0, 1;
  const Eigen::Vector3d t(to_from.x(), to_from.y(), 0.0);
  for (int i = 0; i < 4; ++i) r.corners.row(i) = (rot * r.corners.row(i).transpose() + t).transpose();
  r.normal = rot * r.normal;
  return r;
}

int RgMap::merge(int64_t from, int64_t into, const geometry::Pose2& into_from_from, int64_t t)
{
  Region* src = region(from);
  Region* dst = region(into);
  if (!src || !dst || from == into) throw std::invalid_argument("merge: need two distinct known regions");
  for (auto s : src->segments) {
    s.a = into_from_from * s.a;
    s.b = into_from_from * s.b;
    dst->segments.push_back(s);
  }
  for (auto o : src->objects) {
    o.center = into_from_from * o.center;
    dst->objects.push_back(o);
  }
  for (const auto& o : src->objects3d) dst->objects3d.push_back(moved(o, into_from_from));
  // Bounding box: the union, with the source's corners moved into the target frame.
  const Eigen::Vector2d corners[4] = {src->bbox_min, {src->bbox_min.x(), src->bbox_max.y()}, src->bbox_max,
                                      {src->bbox_max.x(), src->bbox_min.y()}};
  for (const auto& c : corners) {
    const Eigen::Vector2d p = into_from_from * c;
    dst->bbox_min = dst->bbox_min.cwiseMin(p);
    dst->bbox_max = dst->bbox_max.cwiseMax(p);
  }
  dst->nscans += src->nscans;
  dst->utime = t;
  // An operator's name outlives the merge: it named this place.
  if (dst->name.empty()) dst->name = src->name;
  src->state = Region::State::kMerged;
  src->merged_into = into;
  src->utime = t;

  int neutralized = 0;
  for (auto& [id, g] : gateways_) {
    if (g.region_a == from) {
      g.region_a = into;
      g.region_a_from_region_b = into_from_from * g.region_a_from_region_b;
      for (auto& p : g.gateway_points) p = into_from_from * p;
      for (auto& p : g.crossing_points) p = into_from_from * p;
      for (auto& d : g.traversal_directions) d = geometry::normalize_angle(d + into_from_from.theta());
    }
    if (g.region_b == from) {
      g.region_b = into;
      g.region_a_from_region_b = g.region_a_from_region_b * into_from_from.inverse();
    }
    if (!g.neutralized && g.region_b != 0 && g.region_a == g.region_b) {
      g.neutralized = true;
      ++neutralized;
    }
  }
  if (current_region == from) current_region = into;
  utime = std::max(utime, t);
  ++version;
  return neutralized;
}

std::vector<std::string> RgMap::consistency_problems() const
{
  std::vector<std::string> out;
  for (const auto& [id, g] : gateways_) {
    const Region* a = region(g.region_a);
    if (!a) out.push_back("gateway " + std::to_string(id) + ": region_a " + std::to_string(g.region_a) + " missing");
    else if (a->state == Region::State::kMerged) out.push_back("gateway " + std::to_string(id) + " attached to merged region");
    if (g.region_b != 0 && !region(g.region_b))
      out.push_back("gateway " + std::to_string(id) + ": region_b " + std::to_string(g.region_b) + " missing");
    if (g.region_b != 0 && g.region_a == g.region_b && !g.neutralized)
      out.push_back("gateway " + std::to_string(id) + " has one region on both sides but is not neutralized");
  }
  for (const auto& [id, r] : regions_) {
    if (r.state == Region::State::kMerged && resolve(id) == 0)
      out.push_back("region " + std::to_string(id) + ": merge chain is broken or cyclic");
  }
  if (current_region != 0 && (!region(current_region) || region(current_region)->state == Region::State::kMerged))
    out.push_back("current region " + std::to_string(current_region) + " is missing or merged");
  return out;
}

void RgMap::set_next_ids(int64_t region_id, int64_t gateway_id)
{
  int64_t max_r = 0, max_g = 0;
  for (const auto& kv : regions_) max_r = std::max(max_r, kv.first);
  for (const auto& kv : gateways_) max_g = std::max(max_g, kv.first);
  next_region_id_ = std::max(region_id, max_r + 1);
  next_gateway_id_ = std::max(gateway_id, max_g + 1);
}

int64_t region_to_name(const RgMap& map, int64_t id, const std::string& name, std::string* why)
{
  std::string bad;
  const auto no = [&](const std::string& text) {
    if (why) *why = text;
    return int64_t{0};
  };
  if (!valid_region_name(name, &bad)) return no(bad);
  const int64_t live = map.region(id) ? map.resolve(id) : 0;
  const Region* r = live ? map.region(live) : nullptr;
  if (!r || r->state == Region::State::kMerged) return no("no region " + std::to_string(id) + " in the map");
  for (const auto& [other, o] : map.regions())
    if (other != live && o.state != Region::State::kMerged && same_region_name(o.name, name))
      return no("region " + std::to_string(other) + " is named '" + o.name + "' already");
  if (why) why->clear();
  return live;
}

}  // namespace rgnav::rgmap
