#include "rgmap/rgmap_json.h"

#include <cmath>
#include <stdexcept>

namespace rgnav::rgmap {
namespace {

using nlohmann::json;

json pose_json(const geometry::Pose2& p) { return json::array({p.x(), p.y(), p.theta()}); }
json point_json(const Eigen::Vector2d& p) { return json::array({p.x(), p.y()}); }

std::string hex(const std::vector<uint8_t>& bytes)
{
  static const char* digits = "0123456789abcdef";
  std::string s;
  s.reserve(bytes.size() * 2);
  for (uint8_t b : bytes) {
    s.push_back(digits[b >> 4]);
    s.push_back(digits[b & 15]);
  }
  return s;
}

// Reads with a JSON path for messages.
class Reader
{
 public:
  Reader(const json& j, std::string path) : j_(j), path_(std::move(path)) {}
  [[noreturn]] void fail(const std::string& what) const { throw std::invalid_argument("rgmap json " + path_ + ": " + what); }
  Reader at(const std::string& key) const
  {
    if (!j_.is_object() || !j_.contains(key)) fail("missing key '" + key + "'");
    return Reader(j_.at(key), path_ + "." + key);
  }
  Reader at(size_t i) const { return Reader(j_.at(i), path_ + "[" + std::to_string(i) + "]"); }
  bool has(const std::string& key) const { return j_.is_object() && j_.contains(key); }
  size_t size() const
  {
    if (!j_.is_array()) fail("expected an array");
    return j_.size();
  }
  double num() const
  {
    if (!j_.is_number()) fail("expected a number");
    const double v = j_.get<double>();
    if (!std::isfinite(v)) fail("not finite");
    return v;
  }
  int64_t integer() const
  {
    if (!j_.is_number_integer()) fail("expected an integer");
    return j_.get<int64_t>();
  }
  bool boolean() const
  {
    if (!j_.is_boolean()) fail("expected true/false");
    return j_.get<bool>();
  }
  std::string str() const
  {
    if (!j_.is_string()) fail("expected a string");
    return j_.get<std::string>();
  }
  geometry::Pose2 pose() const
  {
    if (size() != 3) fail("expected [x, y, theta]");
    return {at(0).num(), at(1).num(), at(2).num()};
  }
  Eigen::Vector2d point() const
  {
    if (size() != 2) fail("expected [x, y]");
    return {at(0).num(), at(1).num()};
  }
  std::vector<uint8_t> bytes_from_hex() const
  {
    const std::string s = str();
    if (s.size() % 2) fail("odd hex length");
    std::vector<uint8_t> out(s.size() / 2);
    for (size_t i = 0; i < out.size(); ++i) {
      auto nib = [&](char c) -> int {
        if (c >= '0' && c <= '9') return c - '0';
        if (c >= 'a' && c <= 'f') return c - 'a' + 10;
        fail("not a hex digit");
      };
      out[i] = static_cast<uint8_t>(nib(s[2 * i]) << 4 | nib(s[2 * i + 1]));
    }
    return out;
  }

 private:
  const json& j_;
  std::string path_;
};

}  // namespace

json to_json(const RgMap& map)
{
  json j;
  j["schema"] = "rgnav.rgmap";
  j["schema_version"] = kJsonSchemaVersion;
  j["utime"] = map.utime;
  j["version"] = map.version;
  j["current_region"] = map.current_region;
  j["last_scan_id"] = map.last_scan_id;
  j["next_region_id"] = map.next_region_id();
  j["next_gateway_id"] = map.next_gateway_id();
  j["regions"] = json::array();
  for (const auto& [id, r] : map.regions()) {
    json jr;
    jr["id"] = r.id;
    jr["name"] = r.name;
    jr["state"] = static_cast<int>(r.state);
    jr["merged_into"] = r.merged_into;
    jr["utime"] = r.utime;
    jr["map_from_region"] = pose_json(r.map_from_region);
    jr["segments"] = json::array();
    for (const auto& s : r.segments)
      jr["segments"].push_back({{"a", point_json(s.a)}, {"b", point_json(s.b)}, {"sigma", s.sigma}, {"support", s.support}});
    jr["objects"] = json::array();
    for (const auto& o : r.objects)
      jr["objects"].push_back({{"id", o.id}, {"shape", static_cast<int>(o.shape)}, {"center", pose_json(o.center)},
                               {"length", o.length}, {"width", o.width}, {"confidence", o.confidence}});
    jr["objects3d"] = json::array();
    for (const auto& o : r.objects3d) {
      json corners = json::array();
      for (int i = 0; i < 4; ++i) corners.push_back({o.corners(i, 0), o.corners(i, 1), o.corners(i, 2)});
      jr["objects3d"].push_back({{"id", o.id}, {"corners", corners}, {"normal", {o.normal.x(), o.normal.y(), o.normal.z()}},
                                 {"width", o.width}, {"height", o.height}, {"confidence", o.confidence}, {"kind", o.kind}});
    }
    jr["bbox"] = {point_json(r.bbox_min), point_json(r.bbox_max)};
    jr["freespace"] = {{"resolution", r.freespace.resolution()},
                       {"region_from_grid", pose_json(r.freespace.region_from_grid())},
                       {"width", r.freespace.width()},
                       {"height", r.freespace.height()},
                       {"bits_hex", hex(r.freespace.bytes())}};
    jr["accuracy"] = r.accuracy;
    jr["completeness"] = r.completeness;
    jr["nscans"] = r.nscans;
    j["regions"].push_back(jr);
  }
  j["gateways"] = json::array();
  for (const auto& [id, g] : map.gateways()) {
    json jg;
    jg["id"] = g.id;
    jg["class"] = static_cast<int>(g.cls);
    jg["class_name"] = to_string(g.cls);
    jg["region_a"] = g.region_a;
    jg["region_b"] = g.region_b;
    jg["region_a_from_region_b"] = pose_json(g.region_a_from_region_b);
    jg["gateway_points"] = json::array();
    for (const auto& p : g.gateway_points) jg["gateway_points"].push_back(point_json(p));
    jg["crossing_points"] = json::array();
    for (const auto& p : g.crossing_points) jg["crossing_points"].push_back(point_json(p));
    jg["traversal_directions"] = g.traversal_directions;
    jg["traversals"] = g.traversals;
    jg["mean_traversal_time"] = g.mean_traversal_time;
    jg["neutralized"] = g.neutralized;
    j["gateways"].push_back(jg);
  }
  return j;
}

RgMap from_json(const json& j)
{
  const Reader root(j, "$");
  if (root.at("schema").str() != "rgnav.rgmap") root.fail("not an rgnav RG map");
  if (root.at("schema_version").integer() != kJsonSchemaVersion) root.fail("unsupported schema_version");
  RgMap map;
  const Reader regions = root.at("regions");
  for (size_t i = 0; i < regions.size(); ++i) {
    const Reader jr = regions.at(i);
    Region r;
    r.id = jr.at("id").integer();
    r.name = jr.at("name").str();
    const int64_t state = jr.at("state").integer();
    if (state < 1 || state > 3) jr.at("state").fail("unknown region state");
    r.state = static_cast<Region::State>(state);
    r.merged_into = jr.at("merged_into").integer();
    r.utime = jr.at("utime").integer();
    r.map_from_region = jr.at("map_from_region").pose();
    const Reader segs = jr.at("segments");
    for (size_t k = 0; k < segs.size(); ++k) {
      const Reader s = segs.at(k);
      r.segments.push_back({s.at("a").point(), s.at("b").point(), s.at("sigma").num(), static_cast<int>(s.at("support").integer())});
    }
    const Reader objs = jr.at("objects");
    for (size_t k = 0; k < objs.size(); ++k) {
      const Reader o = objs.at(k);
      const int64_t shape = o.at("shape").integer();
      if (shape != 1 && shape != 2) o.at("shape").fail("unknown shape");
      r.objects.push_back({o.at("id").integer(), static_cast<Object2d::Shape>(shape), o.at("center").pose(),
                           o.at("length").num(), o.at("width").num(), o.at("confidence").num()});
    }
    const Reader o3 = jr.at("objects3d");
    for (size_t k = 0; k < o3.size(); ++k) {
      const Reader o = o3.at(k);
      Rectangle3d x;
      x.id = o.at("id").integer();
      const Reader corners = o.at("corners");
      if (corners.size() != 4) corners.fail("expected 4 corners");
      for (size_t c = 0; c < 4; ++c) {
        if (corners.at(c).size() != 3) corners.at(c).fail("expected [x, y, z]");
        for (size_t d = 0; d < 3; ++d) x.corners(static_cast<int>(c), static_cast<int>(d)) = corners.at(c).at(d).num();
      }
      const Reader n = o.at("normal");
      if (n.size() != 3) n.fail("expected [x, y, z]");
      x.normal = Eigen::Vector3d(n.at(0).num(), n.at(1).num(), n.at(2).num());
      x.width = o.at("width").num();
      x.height = o.at("height").num();
      x.confidence = o.at("confidence").num();
      x.kind = static_cast<int8_t>(o.at("kind").integer());
      r.objects3d.push_back(x);
    }
    const Reader bbox = jr.at("bbox");
    if (bbox.size() != 2) bbox.fail("expected [min, max]");
    r.bbox_min = bbox.at(0).point();
    r.bbox_max = bbox.at(1).point();
    const Reader fs = jr.at("freespace");
    const double res = fs.at("resolution").num();
    const int64_t w = fs.at("width").integer(), h = fs.at("height").integer();
    if (!(res > 0) || w < 0 || h < 0 || w > 100000 || h > 100000) fs.fail("bad freespace geometry");
    try {
      r.freespace = FreespaceBitmap(res, fs.at("region_from_grid").pose(), static_cast<int>(w), static_cast<int>(h),
                                    fs.at("bits_hex").bytes_from_hex());
    } catch (const std::invalid_argument& e) {
      fs.fail(e.what());
    }
    r.accuracy = jr.at("accuracy").num();
    r.completeness = jr.at("completeness").num();
    r.nscans = static_cast<int>(jr.at("nscans").integer());
    try {
      map.insert_region(std::move(r));
    } catch (const std::invalid_argument& e) {
      jr.fail(e.what());
    }
  }
  const Reader gateways = root.at("gateways");
  for (size_t i = 0; i < gateways.size(); ++i) {
    const Reader jg = gateways.at(i);
    Gateway g;
    g.id = jg.at("id").integer();
    const int64_t cls = jg.at("class").integer();
    if (cls < 0 || cls > 11) jg.at("class").fail("unknown gateway class");
    g.cls = static_cast<GatewayClass>(cls);
    g.region_a = jg.at("region_a").integer();
    g.region_b = jg.at("region_b").integer();
    g.region_a_from_region_b = jg.at("region_a_from_region_b").pose();
    const Reader gp = jg.at("gateway_points");
    for (size_t k = 0; k < gp.size(); ++k) g.gateway_points.push_back(gp.at(k).point());
    const Reader cp = jg.at("crossing_points");
    for (size_t k = 0; k < cp.size(); ++k) g.crossing_points.push_back(cp.at(k).point());
    const Reader td = jg.at("traversal_directions");
    for (size_t k = 0; k < td.size(); ++k) g.traversal_directions.push_back(td.at(k).num());
    g.traversals = static_cast<int>(jg.at("traversals").integer());
    g.mean_traversal_time = jg.at("mean_traversal_time").num();
    g.neutralized = jg.at("neutralized").boolean();
    try {
      map.insert_gateway(std::move(g));
    } catch (const std::invalid_argument& e) {
      jg.fail(e.what());
    }
  }
  map.utime = root.at("utime").integer();
  map.version = root.at("version").integer();
  map.current_region = root.at("current_region").integer();
  map.last_scan_id = root.at("last_scan_id").integer();
  map.set_next_ids(root.at("next_region_id").integer(), root.at("next_gateway_id").integer());
  const auto problems = map.consistency_problems();
  if (!problems.empty()) root.fail("inconsistent map: " + problems.front());
  return map;
}

}  // namespace rgnav::rgmap
