#include "rgmap/rgmap_conversions.h"

#include "msg/conversions.h"

namespace rgnav::rgmap {
namespace {

template <class T, class F>
auto map_vector(const std::vector<T>& in, F f)
{
  std::vector<decltype(f(in.front()))> out;
  out.reserve(in.size());
  for (const auto& x : in) out.push_back(f(x));
  return out;
}

}  // namespace

region_t to_msg(const Region& r)
{
  region_t m;
  m.utime = r.utime;
  m.id = r.id;
  m.name = r.name;
  m.state = static_cast<int8_t>(r.state);
  m.merged_into = r.merged_into;
  m.map_from_region = msg::to_msg(r.map_from_region);
  m.segments = map_vector(r.segments, [](const LineSegment& s) {
    line_segment_t l;
    l.a = msg::to_point_msg(s.a);
    l.b = msg::to_point_msg(s.b);
    l.sigma = static_cast<float>(s.sigma);
    l.support = s.support;
    return l;
  });
  m.nsegments = static_cast<int32_t>(m.segments.size());
  m.objects = map_vector(r.objects, [](const Object2d& o) {
    object2d_t x;
    x.id = o.id;
    x.shape = static_cast<int8_t>(o.shape);
    x.center = msg::to_msg(o.center);
    x.length = o.length;
    x.width = o.width;
    x.confidence = static_cast<float>(o.confidence);
    return x;
  });
  m.nobjects = static_cast<int32_t>(m.objects.size());
  m.objects3d = map_vector(r.objects3d, [](const Rectangle3d& o) {
    rectangle3d_t x;
    x.id = o.id;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 3; ++j) x.corners[i][j] = o.corners(i, j);
    for (int j = 0; j < 3; ++j) x.normal[j] = o.normal(j);
    x.width = o.width;
    x.height = o.height;
    x.confidence = static_cast<float>(o.confidence);
    x.kind = o.kind;
    return x;
  });
  m.nobjects3d = static_cast<int32_t>(m.objects3d.size());
  m.bbox_min = msg::to_point_msg(r.bbox_min);
  m.bbox_max = msg::to_point_msg(r.bbox_max);
  m.freespace_resolution = static_cast<float>(r.freespace.resolution());
  m.region_from_freespace = msg::to_msg(r.freespace.region_from_grid());
  m.freespace_width = r.freespace.width();
  m.freespace_height = r.freespace.height();
  m.freespace = r.freespace.bytes();
  m.freespace_nbytes = static_cast<int32_t>(m.freespace.size());
  const FreespaceFeatures f = r.freespace.features();
  const double feats[8] = {f.area, f.area * f.centroid.x(), f.area * f.centroid.y(), f.second_moments(0, 0),
                           f.second_moments(0, 1), f.second_moments(1, 1), f.main_axes.x(), f.main_axes.y()};
  std::copy(feats, feats + 8, m.features);
  m.accuracy = static_cast<float>(r.accuracy);
  m.completeness = static_cast<float>(r.completeness);
  m.nscans = r.nscans;
  return m;
}

gateway_t to_msg(const Gateway& g)
{
  gateway_t m;
  m.id = g.id;
  m.gateway_class = static_cast<int8_t>(g.cls);
  m.region_a = g.region_a;
  m.region_b = g.region_b;
  m.region_a_from_region_b = msg::to_msg(g.region_a_from_region_b);
  m.gateway_points = map_vector(g.gateway_points, msg::to_point_msg);
  m.npoints = static_cast<int32_t>(m.gateway_points.size());
  m.crossing_points = map_vector(g.crossing_points, msg::to_point_msg);
  m.ncrossing_points = static_cast<int32_t>(m.crossing_points.size());
  m.traversal_directions = g.traversal_directions;
  m.ndirections = static_cast<int32_t>(m.traversal_directions.size());
  m.traversals = g.traversals;
  m.mean_traversal_time = g.mean_traversal_time;
  m.neutralized = g.neutralized;
  return m;
}

rg_map_t to_msg(const RgMap& map)
{
  rg_map_t m;
  m.utime = map.utime;
  m.version = map.version;
  m.current_region = map.current_region;
  m.last_scan_id = map.last_scan_id;
  for (const auto& kv : map.regions()) m.regions.push_back(to_msg(kv.second));
  m.nregions = static_cast<int32_t>(m.regions.size());
  for (const auto& kv : map.gateways()) m.gateways.push_back(to_msg(kv.second));
  m.ngateways = static_cast<int32_t>(m.gateways.size());
  return m;
}

rg_graph_t to_msg(const RgGraph& g, int64_t utime)
{
  rg_graph_t m;
  m.utime = utime;
  m.map_version = g.map_version;
  for (const auto& n : g.nodes) {
    rg_graph_node_t x;
    x.id = n.id;
    x.region_id = n.region_id;
    x.gateway_id = n.gateway_id;
    x.point = msg::to_point_msg(n.point);
    m.nodes.push_back(x);
  }
  m.nnodes = static_cast<int32_t>(m.nodes.size());
  for (const auto& e : g.edges) {
    rg_graph_edge_t x;
    x.from_node = e.from;
    x.to_node = e.to;
    x.kind = static_cast<int8_t>(e.kind);
    x.region_id = e.region_id;
    x.gateway_id = e.gateway_id;
    x.cost = e.cost;
    x.length = e.length;
    m.edges.push_back(x);
  }
  m.nedges = static_cast<int32_t>(m.edges.size());
  return m;
}

Rectangle3d from_msg(const rectangle3d_t& x)
{
  Rectangle3d o;
  o.id = x.id;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 3; ++j) o.corners(i, j) = x.corners[i][j];
  o.normal = Eigen::Vector3d(x.normal[0], x.normal[1], x.normal[2]);
  o.width = x.width;
  o.height = x.height;
  o.confidence = x.confidence;
  o.kind = x.kind;
  return o;
}

Region from_msg(const region_t& m)
{
  Region r;
  r.utime = m.utime;
  r.id = m.id;
  r.name = m.name;
  r.state = static_cast<Region::State>(m.state);
  r.merged_into = m.merged_into;
  r.map_from_region = msg::to_pose2(m.map_from_region);
  r.segments = map_vector(m.segments, [](const line_segment_t& l) {
    return LineSegment{msg::to_vector(l.a), msg::to_vector(l.b), l.sigma, l.support};
  });
  r.objects = map_vector(m.objects, [](const object2d_t& x) {
    return Object2d{x.id, static_cast<Object2d::Shape>(x.shape), msg::to_pose2(x.center), x.length, x.width, x.confidence};
  });
  r.objects3d = map_vector(m.objects3d, [](const rectangle3d_t& x) { return from_msg(x); });
  r.bbox_min = msg::to_vector(m.bbox_min);
  r.bbox_max = msg::to_vector(m.bbox_max);
  if (m.freespace_width > 0 && m.freespace_height > 0)
    r.freespace = FreespaceBitmap(m.freespace_resolution, msg::to_pose2(m.region_from_freespace), m.freespace_width,
                                  m.freespace_height, m.freespace);
  r.accuracy = m.accuracy;
  r.completeness = m.completeness;
  r.nscans = m.nscans;
  return r;
}

Gateway from_msg(const gateway_t& m)
{
  Gateway g;
  g.id = m.id;
  g.cls = static_cast<GatewayClass>(m.gateway_class);
  g.region_a = m.region_a;
  g.region_b = m.region_b;
  g.region_a_from_region_b = msg::to_pose2(m.region_a_from_region_b);
  g.gateway_points = map_vector(m.gateway_points, msg::to_vector);
  g.crossing_points = map_vector(m.crossing_points, msg::to_vector);
  g.traversal_directions = m.traversal_directions;
  g.traversals = m.traversals;
  g.mean_traversal_time = m.mean_traversal_time;
  g.neutralized = m.neutralized;
  return g;
}

RgMap from_msg(const rg_map_t& m)
{
  RgMap map;
  for (const auto& r : m.regions) map.insert_region(from_msg(r));
  for (const auto& g : m.gateways) map.insert_gateway(from_msg(g));
  map.utime = m.utime;
  map.version = m.version;
  map.current_region = m.current_region;
  map.last_scan_id = m.last_scan_id;
  return map;
}

}  // namespace rgnav::rgmap
