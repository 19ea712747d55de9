#include "viewer/region_json.h"

#include <nlohmann/json.hpp>

#include "viewer/json_geometry.h"

namespace rgnav::viewer {

namespace {

using nlohmann::json;

const char* region_state_name(rgmap::Region::State s)
{
  switch (s) {
    case rgmap::Region::State::kOpen: return "open";
    case rgmap::Region::State::kFinalised: return "finalised";
    case rgmap::Region::State::kMerged: return "merged";
  }
  return "?";
}

std::string base64(const std::vector<uint8_t>& bytes)
{
  static const char* chars = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const uint32_t n = (uint32_t{bytes[i]} << 16) | (i + 1 < bytes.size() ? uint32_t{bytes[i + 1]} << 8 : 0) |
                       (i + 2 < bytes.size() ? uint32_t{bytes[i + 2]} : 0);
    out.push_back(chars[(n >> 18) & 63]);
    out.push_back(chars[(n >> 12) & 63]);
    out.push_back(i + 1 < bytes.size() ? chars[(n >> 6) & 63] : '=');
    out.push_back(i + 2 < bytes.size() ? chars[n & 63] : '=');
  }
  return out;
}

// The freespace bitmap as it is (1 bit per cell, row-major, LSB first, base64): the page paints
// it through map_from_grid, so a region shows its real shape, not its bounding rectangle.
json freespace_json(const rgmap::Region& r)
{
  const auto& f = r.freespace;
  if (f.width() <= 0 || f.height() <= 0) return nullptr;
  return {{"width", f.width()},
          {"height", f.height()},
          {"resolution", f.resolution()},
          {"frame", pose_array(r.map_from_region * f.region_from_grid())},
          {"bits", base64(f.bytes())}};
}

}  // namespace

json region_json(const rgmap::Region& r)
{
  const geometry::Pose2& m = r.map_from_region;
  json segments = json::array();
  for (const auto& s : r.segments) {
    json seg = json::array();
    append_point(seg, m * s.a);
    append_point(seg, m * s.b);
    segments.push_back(std::move(seg));
  }
  json objects = json::array();
  for (const auto& o : r.objects) {
    objects.push_back({{"shape", o.shape == rgmap::Object2d::Shape::kCircle ? "circle" : "rectangle"},
                       {"pose", pose_array(m * o.center)},
                       {"length", r3(o.length)},
                       {"width", r3(o.width)}});
  }
  // The bounding rectangle is in the region frame: its four corners in the map frame.
  json outline = json::array();
  const Eigen::Vector2d lo = r.bbox_min, hi = r.bbox_max;
  for (const Eigen::Vector2d& c : {lo, Eigen::Vector2d(hi.x(), lo.y()), hi, Eigen::Vector2d(lo.x(), hi.y())})
    append_point(outline, m * c);
  json centre = json::array();
  append_point(centre, m * Eigen::Vector2d(0.5 * (lo + hi)));
  return {{"id", r.id},
          {"name", r.name},
          {"state", region_state_name(r.state)},
          {"frame", pose_array(m)},
          {"outline", std::move(outline)},
          {"centre", std::move(centre)},
          {"segments", std::move(segments)},
          {"objects", std::move(objects)},
          {"freespace", freespace_json(r)},
          {"nscans", r.nscans}};
}


}  // namespace rgnav::viewer
