#include "sample_messages.h"

#include <cmath>
#include <string>

namespace rgnav::testing {
namespace {

// Small deterministic generator (splitmix64): samples must not depend on the platform's
// std:: distributions, so a failure reproduces everywhere.
class Gen
{
 public:
  explicit Gen(uint32_t variant, uint64_t salt) : s_(variant * 0x9E3779B97F4A7C15ull + salt) {}
  uint64_t next()
  {
    uint64_t z = (s_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double uniform(double lo, double hi) { return lo + (hi - lo) * (next() >> 11) * 0x1.0p-53; }
  int count(int lo, int hi) { return lo + static_cast<int>(next() % static_cast<uint64_t>(hi - lo + 1)); }
  template <class E>
  E pick(std::initializer_list<E> values)
  {
    return *(values.begin() + next() % values.size());
  }
  std::string word(const char* prefix) { return std::string(prefix) + "_" + std::to_string(next() % 1000); }

 private:
  uint64_t s_;
};

// Per-type salts so that e.g. sample<pose2d_t>(0) and sample<point2d_t>(0) differ.
constexpr uint64_t kSalt = 0x5EEDull;

point2d_t point(Gen& g)
{
  point2d_t p;
  p.x = g.uniform(-20, 20);
  p.y = g.uniform(-20, 20);
  return p;
}

pose2d_t pose(Gen& g)
{
  pose2d_t p;
  p.x = g.uniform(-50, 50);
  p.y = g.uniform(-50, 50);
  p.theta = g.uniform(-M_PI + 1e-9, M_PI);
  return p;
}

void covariance(Gen& g, double (&c)[9])
{
  for (double& v : c) v = 0;
  c[0] = g.uniform(1e-4, 0.1);
  c[4] = g.uniform(1e-4, 0.1);
  c[8] = g.uniform(1e-5, 0.05);
  c[1] = c[3] = g.uniform(-1e-4, 1e-4);
}

void class_probabilities(Gen& g, float (&p)[12])
{
  double sum = 0;
  double raw[12];
  for (double& r : raw) sum += (r = g.uniform(0.01, 1.0));
  for (int i = 0; i < 12; ++i) p[i] = static_cast<float>(raw[i] / sum);
}

std::vector<point2d_t> points(Gen& g, int lo, int hi)
{
  std::vector<point2d_t> v(static_cast<size_t>(g.count(lo, hi)));
  for (auto& p : v) p = point(g);
  return v;
}

std::vector<double> angles(Gen& g, int lo, int hi)
{
  std::vector<double> v(static_cast<size_t>(g.count(lo, hi)));
  for (auto& a : v) a = g.uniform(-M_PI, M_PI);
  return v;
}

// The point lists of a gateway, in a gateway_t or a gateway_hypothesis_t (the same fields).
template <class M>
void gateway_geometry(Gen& g, M& m)
{
  m.gateway_points = points(g, 0, 4);
  m.npoints = static_cast<int32_t>(m.gateway_points.size());
  m.crossing_points = points(g, 0, 3);
  m.ncrossing_points = static_cast<int32_t>(m.crossing_points.size());
  m.traversal_directions = angles(g, 0, 4);
  m.ndirections = static_cast<int32_t>(m.traversal_directions.size());
}

// The `n` elements of a message's list: sample<T> of variants first, first + 1, ...
template <class T>
std::vector<T> samples(int n, uint32_t first)
{
  std::vector<T> v;
  for (int i = 0; i < n; ++i) v.push_back(sample<T>(first + i));
  return v;
}

int64_t utime(Gen& g) { return 1'700'000'000'000'000 + static_cast<int64_t>(g.next() % 1'000'000'000'000); }

}  // namespace

laser_scan_t sample_laser_scan(int64_t scan_id, int beams, uint32_t variant)
{
  Gen g(variant, kSalt + 1);
  laser_scan_t m;
  m.utime = utime(g);
  m.scan_id = scan_id;
  m.sensor = "laser_front";
  m.angle_min = static_cast<float>(-M_PI / 2);
  m.angle_increment = static_cast<float>(M_PI / (beams - 1));
  m.range_min = 0.0f;
  m.range_max = 8.0f;
  m.scan_time = 1.0f / 75.0f;
  m.nranges = beams;
  m.ranges.resize(static_cast<size_t>(beams));
  for (auto& r : m.ranges) {
    const uint64_t k = g.next() % 20;
    r = k == 0 ? m.range_max : k == 1 ? 0.0f : static_cast<float>(g.uniform(0.05, 7.99));
  }
  const bool with_intensity = variant % 2 == 1;
  m.nintensities = with_intensity ? beams : 0;
  m.intensities.resize(static_cast<size_t>(m.nintensities));
  for (auto& i : m.intensities) i = static_cast<float>(g.count(0, 255));
  return m;
}

image_t sample_image(int width, int height, int32_t pixel_format, int row_stride, uint32_t variant)
{
  Gen g(variant, kSalt + 2);
  image_t m;
  m.utime = utime(g);
  m.width = width;
  m.height = height;
  m.pixel_format = pixel_format;
  const int bpp = pixel_format == image_t::FORMAT_BGR8 ? 3 : 1;
  m.row_stride = row_stride > 0 ? row_stride : width * bpp;
  m.size = m.row_stride * height;
  m.data.resize(static_cast<size_t>(m.size));
  const auto seed = static_cast<uint8_t>(g.next());
  for (size_t i = 0; i < m.data.size(); ++i) m.data[i] = static_cast<uint8_t>(seed + i * 7 + (i >> 9));
  return m;
}

stereo_images_t sample_stereo(int64_t frame_id, int width, int height, int32_t pixel_format)
{
  Gen g(static_cast<uint32_t>(frame_id), kSalt + 3);
  stereo_images_t m;
  m.left = sample_image(width, height, pixel_format, 0, static_cast<uint32_t>(2 * frame_id));
  m.right = sample_image(width, height, pixel_format, 0, static_cast<uint32_t>(2 * frame_id + 1));
  m.utime = m.left.utime;
  m.right.utime = m.left.utime + 40;
  m.frame_id = frame_id;
  m.calibration_id = "stereo_b21r";
  m.pan = g.uniform(-1.5, 1.5);
  m.tilt = g.uniform(-0.5, 0.5);
  return m;
}

template <>
point2d_t sample<point2d_t>(uint32_t variant)
{
  Gen g(variant, kSalt + 10);
  return point(g);
}

template <>
pose2d_t sample<pose2d_t>(uint32_t variant)
{
  Gen g(variant, kSalt + 11);
  return pose(g);
}

template <>
laser_scan_t sample<laser_scan_t>(uint32_t variant)
{
  return sample_laser_scan(1 + variant, variant % 3 == 2 ? 361 : 181, variant);
}

template <>
image_t sample<image_t>(uint32_t variant)
{
  Gen g(variant, kSalt + 12);
  switch (variant % 3) {
    case 0: return sample_image(g.count(4, 24), g.count(3, 16), image_t::FORMAT_GRAY8, 0, variant);
    case 1: return sample_image(g.count(4, 16), g.count(3, 12), image_t::FORMAT_BGR8, 64, variant);
    default: {
      // A (tiny, not decodable as a picture) JPEG byte stream: SOI marker, payload, EOI.
      image_t m;
      m.utime = utime(g);
      m.width = 640;
      m.height = 480;
      m.row_stride = 0;
      m.pixel_format = image_t::FORMAT_JPEG;
      m.data = {0xFF, 0xD8, 0xFF, 0xE0};
      for (int i = g.count(4, 40); i > 0; --i) m.data.push_back(static_cast<uint8_t>(g.next()));
      m.data.push_back(0xFF);
      m.data.push_back(0xD9);
      m.size = static_cast<int32_t>(m.data.size());
      return m;
    }
  }
}

template <>
stereo_images_t sample<stereo_images_t>(uint32_t variant)
{
  Gen g(variant, kSalt + 13);
  return sample_stereo(1 + variant, g.count(4, 20), g.count(3, 12),
                       variant % 2 ? int32_t{image_t::FORMAT_BGR8} : int32_t{image_t::FORMAT_GRAY8});
}

template <>
odometry_t sample<odometry_t>(uint32_t variant)
{
  Gen g(variant, kSalt + 14);
  odometry_t m;
  m.utime = utime(g);
  m.seq = 1 + variant;
  m.odom_from_base = pose(g);
  m.v = g.uniform(-0.8, 0.8);
  m.omega = g.uniform(-1.5, 1.5);
  m.distance = g.uniform(0, 1000);
  m.status = g.pick<int8_t>({odometry_t::STATUS_OK, odometry_t::STATUS_STOPPED, odometry_t::STATUS_FAULT,
                             odometry_t::STATUS_SIMULATED});
  return m;
}

template <>
velocity_cmd_t sample<velocity_cmd_t>(uint32_t variant)
{
  Gen g(variant, kSalt + 15);
  velocity_cmd_t m;
  m.utime = utime(g);
  m.seq = 1 + variant;
  m.v = g.uniform(-1, 1);
  m.omega = g.uniform(-2, 2);
  m.deadline_us = g.count(50'000, 500'000);
  m.source = g.pick<const char*>({"lld", "teleop", "test"});
  return m;
}

template <>
heartbeat_t sample<heartbeat_t>(uint32_t variant)
{
  Gen g(variant, kSalt + 16);
  heartbeat_t m;
  m.utime = utime(g);
  m.name = g.word("proc");
  m.host = "b21r";
  m.pid = g.count(2, 4'000'000);
  m.seq = 1 + variant;
  m.state = g.pick<int8_t>({heartbeat_t::STATE_STARTING, heartbeat_t::STATE_RUNNING, heartbeat_t::STATE_DEGRADED,
                            heartbeat_t::STATE_STOPPING});
  m.last_input_age_us = variant % 4 == 0 ? -1 : g.count(0, 2'000'000);
  m.cpu_percent = static_cast<float>(g.uniform(0, 100));
  m.rss_kb = g.count(1000, 500'000);
  m.messages_in = g.count(0, 100'000);
  m.messages_dropped = g.count(0, 10);
  m.status = variant % 3 == 0 ? "" : "ok \"quoted\" \\ status";
  m.progress = g.count(0, 1'000'000);
  m.busy_ms = variant % 2 ? 0 : g.count(1, 60'000);
  return m;
}

template <>
process_status_t sample<process_status_t>(uint32_t variant)
{
  Gen g(variant, kSalt + 17);
  process_status_t m;
  m.name = g.word("proc");
  m.group = variant % 2 ? "" : "navigation";
  m.state = g.pick<int8_t>({process_status_t::STATE_STOPPED, process_status_t::STATE_STARTING,
                            process_status_t::STATE_RUNNING, process_status_t::STATE_HUNG,
                            process_status_t::STATE_BACKOFF, process_status_t::STATE_FAILED,
                            process_status_t::STATE_STOPPING});
  m.pid = g.count(0, 4'000'000);
  m.restarts = g.count(0, 5);
  m.last_exit = g.pick<const char*>({"", "exit 1", "signal 9", "heartbeat timeout"});
  m.heartbeat_age_us = g.count(-1, 3'000'000);
  m.cpu_percent = static_cast<float>(g.uniform(0, 150));
  m.rss_kb = g.count(0, 900'000);
  return m;
}

template <>
supervisor_status_t sample<supervisor_status_t>(uint32_t variant)
{
  Gen g(variant, kSalt + 18);
  supervisor_status_t m;
  m.utime = utime(g);
  m.host = "b21r";
  m.config = "deploy/sim.yaml";
  m.nprocesses = g.count(0, 6);
  m.processes = samples<process_status_t>(m.nprocesses, variant * 7);
  m.robot_held = variant % 2 == 1;
  m.alert = m.robot_held ? "lld failed: robot held" : "";
  m.host_stalls = variant % 3 == 0 ? 0 : g.count(1, 500);
  m.host_stall_max_ms = m.host_stalls == 0 ? 0 : g.count(50, 2000);
  m.host_stall_total_ms = m.host_stalls == 0 ? 0 : m.host_stall_max_ms * m.host_stalls;
  return m;
}

template <>
supervisor_order_t sample<supervisor_order_t>(uint32_t variant)
{
  Gen g(variant, kSalt + 19);
  supervisor_order_t m;
  m.utime = utime(g);
  m.order_id = 1 + variant;
  m.host = variant % 2 ? "" : "b21r";
  m.order = g.pick<int8_t>({supervisor_order_t::ORDER_START, supervisor_order_t::ORDER_STOP,
                            supervisor_order_t::ORDER_RESTART, supervisor_order_t::ORDER_SHUTDOWN});
  m.target = m.order == supervisor_order_t::ORDER_SHUTDOWN ? "" : g.word("proc");
  m.source = "rgnav_ctl@" + g.word("host") + ":" + std::to_string(100 + variant);
  m.nonce = static_cast<int64_t>(variant) * 7919 + 13;
  m.key_id = variant % 3 ? "0123456789abcdef" : "";
  m.mac = m.key_id.empty() ? "" : std::string(64, "0123456789abcdef"[variant % 16]);
  return m;
}

template <>
line_segment_t sample<line_segment_t>(uint32_t variant)
{
  Gen g(variant, kSalt + 20);
  line_segment_t m;
  m.a = point(g);
  m.b = point(g);
  m.sigma = static_cast<float>(g.uniform(0.001, 0.05));
  m.support = g.count(2, 400);
  return m;
}

template <>
object2d_t sample<object2d_t>(uint32_t variant)
{
  Gen g(variant, kSalt + 21);
  object2d_t m;
  m.id = 1 + variant;
  m.shape = g.pick<int8_t>({object2d_t::SHAPE_RECTANGLE, object2d_t::SHAPE_CIRCLE});
  m.center = pose(g);
  m.length = g.uniform(0.2, 3);
  m.width = m.shape == object2d_t::SHAPE_CIRCLE ? m.length : g.uniform(0.2, 2);
  m.confidence = static_cast<float>(g.uniform(0, 1));
  return m;
}

template <>
rectangle3d_t sample<rectangle3d_t>(uint32_t variant)
{
  Gen g(variant, kSalt + 22);
  rectangle3d_t m;
  m.id = 1 + variant;
  m.width = g.uniform(0.5, 2);
  m.height = g.uniform(0.5, 2.2);
  const double x = g.uniform(1, 6), y = g.uniform(-3, 3);
  const double z0 = 0, z1 = m.height;
  const double corners[4][3] = {{x, y - m.width / 2, z0}, {x, y + m.width / 2, z0},
                                {x, y + m.width / 2, z1}, {x, y - m.width / 2, z1}};
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) m.corners[i][k] = corners[i][k];
  m.normal[0] = -1;
  m.normal[1] = 0;
  m.normal[2] = 0;
  m.confidence = static_cast<float>(g.uniform(0, 1));
  m.kind = g.pick<int8_t>({rectangle3d_t::KIND_UNKNOWN, rectangle3d_t::KIND_DOOR, rectangle3d_t::KIND_WHITEBOARD,
                           rectangle3d_t::KIND_MONITOR, rectangle3d_t::KIND_TABLE});
  return m;
}

template <>
objects3d_t sample<objects3d_t>(uint32_t variant)
{
  Gen g(variant, kSalt + 23);
  objects3d_t m;
  m.utime = utime(g);
  m.frame_id = 1 + variant;
  m.scan_id = variant;
  m.odom_from_base = pose(g);
  m.nrectangles = g.count(0, 4);
  m.rectangles = samples<rectangle3d_t>(m.nrectangles, variant * 5);
  return m;
}

template <>
obstacle_grid_t sample<obstacle_grid_t>(uint32_t variant)
{
  Gen g(variant, kSalt + 24);
  obstacle_grid_t m;
  m.utime = utime(g);
  m.odom_from_grid = pose(g);
  m.resolution = 0.05f;
  m.width = g.count(0, 30);
  m.height = g.count(1, 20);
  m.ncells = m.width * m.height;
  m.cells.resize(static_cast<size_t>(m.ncells));
  for (auto& c : m.cells) c = static_cast<int8_t>(g.count(-1, 100));
  m.min_height = 0.05f;
  m.max_height = 1.8f;
  return m;
}

template <>
aligned_scan_t sample<aligned_scan_t>(uint32_t variant)
{
  Gen g(variant, kSalt + 25);
  aligned_scan_t m;
  m.scan = sample<laser_scan_t>(variant);
  m.utime = m.scan.utime;
  m.scan_id = m.scan.scan_id;
  m.revision = g.count(0, 3);
  m.odom_from_base = pose(g);
  m.map_from_base = pose(g);
  covariance(g, m.covariance);
  m.base_from_laser.x = 0.12;
  m.base_from_laser.y = 0;
  m.base_from_laser.theta = 0;
  return m;
}

template <>
slam_pose_t sample<slam_pose_t>(uint32_t variant)
{
  Gen g(variant, kSalt + 26);
  slam_pose_t m;
  m.utime = utime(g);
  m.scan_id = 1 + variant;
  m.map_from_base = pose(g);
  covariance(g, m.covariance);
  m.map_from_odom = pose(g);
  return m;
}

template <>
gateway_hypothesis_t sample<gateway_hypothesis_t>(uint32_t variant)
{
  Gen g(variant, kSalt + 27);
  gateway_hypothesis_t m;
  m.track_id = 1 + variant;
  m.gateway_class = static_cast<int8_t>(g.count(0, gateway_hypothesis_t::NUM_CLASSES - 1));
  class_probabilities(g, m.class_probability);
  gateway_geometry(g, m);
  m.distance = static_cast<float>(g.uniform(0.2, 6));
  m.observations = g.count(1, 40);
  return m;
}

template <>
gateway_hypotheses_t sample<gateway_hypotheses_t>(uint32_t variant)
{
  Gen g(variant, kSalt + 28);
  gateway_hypotheses_t m;
  m.utime = utime(g);
  m.scan_id = 1 + variant;
  m.map_from_base = pose(g);
  m.nhypotheses = g.count(0, 4);
  m.hypotheses = samples<gateway_hypothesis_t>(m.nhypotheses, variant * 5);
  return m;
}

template <>
gateway_event_t sample<gateway_event_t>(uint32_t variant)
{
  Gen g(variant, kSalt + 29);
  gateway_event_t m;
  m.utime = utime(g);
  m.scan_id = 1 + variant;
  m.event = g.pick<int8_t>({gateway_event_t::EVENT_APPROACHED, gateway_event_t::EVENT_ENTERED,
                            gateway_event_t::EVENT_TRAVERSED, gateway_event_t::EVENT_LOST});
  m.track_id = g.count(1, 100);
  m.gateway_class = static_cast<int8_t>(g.count(0, 11));
  class_probabilities(g, m.class_probability);
  m.map_from_base = pose(g);
  m.gateway_points = points(g, 0, 4);
  m.npoints = static_cast<int32_t>(m.gateway_points.size());
  m.direction = g.uniform(-M_PI, M_PI);
  return m;
}

template <>
gateway_t sample<gateway_t>(uint32_t variant)
{
  Gen g(variant, kSalt + 30);
  gateway_t m;
  m.id = 1 + variant;
  m.gateway_class = static_cast<int8_t>(g.count(0, 11));
  m.region_a = g.count(1, 50);
  m.region_b = variant % 3 == 0 ? 0 : g.count(1, 50);
  m.region_a_from_region_b = pose(g);
  gateway_geometry(g, m);
  m.traversals = g.count(0, 20);
  m.mean_traversal_time = g.uniform(0, 30);
  m.neutralized = variant % 5 == 4;
  return m;
}

template <>
region_t sample<region_t>(uint32_t variant)
{
  Gen g(variant, kSalt + 31);
  region_t m;
  m.utime = utime(g);
  m.id = 1 + variant;
  m.name = variant % 2 ? "" : g.word("room");
  m.state = g.pick<int8_t>({region_t::STATE_OPEN, region_t::STATE_FINALISED, region_t::STATE_MERGED});
  m.merged_into = m.state == region_t::STATE_MERGED ? g.count(1, 50) : 0;
  m.map_from_region = pose(g);
  m.nsegments = g.count(0, 5);
  m.segments = samples<line_segment_t>(m.nsegments, variant * 7);
  m.nobjects = g.count(0, 3);
  m.objects = samples<object2d_t>(m.nobjects, variant * 7);
  m.nobjects3d = g.count(0, 2);
  m.objects3d = samples<rectangle3d_t>(m.nobjects3d, variant * 7);
  m.bbox_min = point(g);
  m.bbox_max.x = m.bbox_min.x + g.uniform(1, 10);
  m.bbox_max.y = m.bbox_min.y + g.uniform(1, 10);
  m.freespace_resolution = 0.1f;
  m.region_from_freespace = pose(g);
  m.freespace_width = g.count(0, 20);
  m.freespace_height = g.count(0, 17);
  m.freespace_nbytes = (m.freespace_width * m.freespace_height + 7) / 8;
  m.freespace.resize(static_cast<size_t>(m.freespace_nbytes));
  for (auto& b : m.freespace) b = static_cast<uint8_t>(g.next());
  for (double& f : m.features) f = g.uniform(-100, 100);
  m.accuracy = static_cast<float>(g.uniform(0, 1));
  m.completeness = static_cast<float>(g.uniform(0, 1));
  m.nscans = g.count(0, 500);
  return m;
}

template <>
rg_map_t sample<rg_map_t>(uint32_t variant)
{
  Gen g(variant, kSalt + 32);
  rg_map_t m;
  m.utime = utime(g);
  m.version = 1 + variant;
  m.nregions = g.count(0, 3);
  m.regions = samples<region_t>(m.nregions, variant * 4);
  m.ngateways = g.count(0, 3);
  m.gateways = samples<gateway_t>(m.ngateways, variant * 4);
  m.current_region = m.nregions > 0 ? m.regions[0].id : 0;
  m.last_scan_id = g.count(0, 100000);
  return m;
}

template <>
rg_graph_node_t sample<rg_graph_node_t>(uint32_t variant)
{
  Gen g(variant, kSalt + 33);
  rg_graph_node_t m;
  m.id = 1 + variant;
  m.region_id = g.count(1, 50);
  m.gateway_id = g.count(1, 50);
  m.point = point(g);
  return m;
}

template <>
rg_graph_edge_t sample<rg_graph_edge_t>(uint32_t variant)
{
  Gen g(variant, kSalt + 34);
  rg_graph_edge_t m;
  m.from_node = g.count(1, 50);
  m.to_node = g.count(1, 50);
  m.kind = g.pick<int8_t>({rg_graph_edge_t::KIND_REGION, rg_graph_edge_t::KIND_GATEWAY});
  m.region_id = m.kind == rg_graph_edge_t::KIND_REGION ? g.count(1, 50) : 0;
  m.gateway_id = m.kind == rg_graph_edge_t::KIND_GATEWAY ? g.count(1, 50) : 0;
  m.length = g.uniform(0, 20);
  m.cost = m.length / 0.5;
  return m;
}

template <>
rg_graph_t sample<rg_graph_t>(uint32_t variant)
{
  Gen g(variant, kSalt + 35);
  rg_graph_t m;
  m.utime = utime(g);
  m.map_version = 1 + variant;
  m.nnodes = g.count(0, 6);
  m.nodes = samples<rg_graph_node_t>(m.nnodes, variant * 9);
  m.nedges = g.count(0, 6);
  m.edges = samples<rg_graph_edge_t>(m.nedges, variant * 9);
  return m;
}

template <>
region_waypoint_t sample<region_waypoint_t>(uint32_t variant)
{
  Gen g(variant, kSalt + 36);
  region_waypoint_t m;
  m.region_id = g.count(1, 50);
  m.gateway_id = variant % 2 ? 0 : g.count(1, 50);
  m.pose = pose(g);
  return m;
}

template <>
global_path_t sample<global_path_t>(uint32_t variant)
{
  Gen g(variant, kSalt + 37);
  global_path_t m;
  m.utime = utime(g);
  m.goal_id = 1 + variant;
  m.map_version = g.count(1, 1000);
  m.cost = g.uniform(0, 300);
  m.nwaypoints = g.count(0, 6);
  m.waypoints = samples<region_waypoint_t>(m.nwaypoints, variant * 9);
  m.status = g.pick<int8_t>({global_path_t::STATUS_OK, global_path_t::STATUS_NO_PATH,
                             global_path_t::STATUS_GOAL_REACHED, global_path_t::STATUS_CANCELLED});
  m.reason = variant % 2 ? "" : g.word("through gateway");
  return m;
}

template <>
region_pose_t sample<region_pose_t>(uint32_t variant)
{
  Gen g(variant, kSalt + 38);
  region_pose_t m;
  m.utime = utime(g);
  m.scan_id = 1 + variant;
  m.region_id = g.count(1, 50);
  m.region_from_base = pose(g);
  m.map_from_base = pose(g);
  m.odom_from_base = pose(g);
  covariance(g, m.covariance);
  m.confidence = static_cast<float>(g.uniform(0, 1));
  return m;
}

template <>
nav_goal_t sample<nav_goal_t>(uint32_t variant)
{
  Gen g(variant, kSalt + 39);
  nav_goal_t m;
  m.utime = utime(g);
  m.goal_id = 1 + variant;
  const bool by_name = variant % 2 == 1;
  m.region_id = by_name ? 0 : g.count(1, 50);
  m.region_name = by_name ? g.word("room") : "";
  m.has_pose = variant % 3 != 1;
  m.region_from_goal = pose(g);
  m.position_tolerance = g.uniform(0.05, 0.5);
  m.heading_tolerance = variant % 3 == 0 ? M_PI : g.uniform(0.05, 0.5);
  m.beyond_known = variant % 5 == 2;
  m.cancel = variant % 4 == 3;
  return m;
}

template <>
localize_request_t sample<localize_request_t>(uint32_t variant)
{
  Gen g(variant, kSalt + 44);
  localize_request_t m;
  m.utime = utime(g);
  m.mode = variant % 4 == 3 ? localize_request_t::MODE_GLOBAL : localize_request_t::MODE_POSE;
  const bool by_name = variant % 2 == 1;
  m.region_id = by_name ? 0 : g.count(1, 50);
  m.region_name = by_name ? g.word("room") : "";
  m.region_from_base = pose(g);
  m.sigma_xy = variant % 3 == 0 ? 0.0 : g.uniform(0.05, 1.0);
  m.sigma_theta = variant % 3 == 0 ? 0.0 : g.uniform(0.02, 0.5);
  return m;
}

template <>
gateway_passed_t sample<gateway_passed_t>(uint32_t variant)
{
  Gen g(variant, kSalt + 45);
  gateway_passed_t m;
  m.utime = utime(g);
  m.gateway_id = g.count(1, 80);
  m.from_region = g.count(1, 50);
  m.to_region = g.count(1, 50);
  m.region_from_base = pose(g);
  m.distance_past = g.uniform(0.5, 2.0);
  return m;
}

template <>
region_name_t sample<region_name_t>(uint32_t variant)
{
  Gen g(variant, kSalt + 46);
  region_name_t m;
  m.utime = utime(g);
  m.region_id = g.count(1, 50);
  m.name = variant % 2 ? g.word("Room") : g.word("hallway east");
  return m;
}

template <>
ca_status_t sample<ca_status_t>(uint32_t variant)
{
  Gen g(variant, kSalt + 47);
  ca_status_t m;
  m.utime = utime(g);
  m.goal_id = variant;
  m.mode = g.pick<int8_t>({ca_status_t::MODE_IDLE, ca_status_t::MODE_PLANNED, ca_status_t::MODE_REACTIVE,
                           ca_status_t::MODE_BLOCKED, ca_status_t::MODE_STALE_STOP, ca_status_t::MODE_ARRIVED});
  const bool stuck = m.mode == ca_status_t::MODE_REACTIVE || m.mode == ca_status_t::MODE_BLOCKED;
  m.blocked_s = stuck ? g.uniform(0, 30) : 0.0;
  m.next_target = g.count(0, 6);
  m.status = g.word("planned");
  return m;
}

template <>
target_list_t sample<target_list_t>(uint32_t variant)
{
  Gen g(variant, kSalt + 40);
  target_list_t m;
  m.utime = utime(g);
  m.goal_id = variant;
  m.ntargets = g.count(0, 6);
  for (int i = 0; i < m.ntargets; ++i) m.odom_from_target.push_back(pose(g));
  m.max_speed = static_cast<float>(g.uniform(0.1, 1.0));
  m.final_is_goal = variant % 2 == 0;
  return m;
}

template <>
trajectory_segment_t sample<trajectory_segment_t>(uint32_t variant)
{
  Gen g(variant, kSalt + 41);
  trajectory_segment_t m;
  m.kind = g.pick<int8_t>({trajectory_segment_t::KIND_LINE, trajectory_segment_t::KIND_ARC,
                           trajectory_segment_t::KIND_CLOTHOID, trajectory_segment_t::KIND_CONIC,
                           trajectory_segment_t::KIND_TURN});
  m.start = pose(g);
  m.length = m.kind == trajectory_segment_t::KIND_TURN ? 0 : g.uniform(0.1, 3);
  m.kappa0 = m.kind == trajectory_segment_t::KIND_LINE ? 0 : g.uniform(-2, 2);
  m.kappa1 = m.kind == trajectory_segment_t::KIND_CLOTHOID ? g.uniform(-2, 2) : m.kappa0;
  for (double& p : m.param) p = g.uniform(-1, 1);
  m.v_max = g.uniform(0.1, 1);
  m.v_end = g.uniform(0, m.v_max);
  return m;
}

template <>
trajectory_t sample<trajectory_t>(uint32_t variant)
{
  Gen g(variant, kSalt + 42);
  trajectory_t m;
  m.utime = utime(g);
  m.trajectory_id = 1 + variant;
  m.frame = trajectory_t::FRAME_ODOM;
  m.nsegments = g.count(0, 5);
  m.segments = samples<trajectory_segment_t>(m.nsegments, variant * 6);
  m.a_max = g.uniform(0.2, 1);
  m.omega_max = g.uniform(0.5, 2);
  m.predicted_end_utime = m.utime + g.count(0, 30'000'000);
  m.stop_at_end = variant % 2 == 0;
  return m;
}

template <>
lld_status_t sample<lld_status_t>(uint32_t variant)
{
  Gen g(variant, kSalt + 43);
  lld_status_t m;
  m.utime = utime(g);
  m.trajectory_id = variant;
  m.state = g.pick<int8_t>({lld_status_t::STATE_IDLE, lld_status_t::STATE_TRACKING, lld_status_t::STATE_DONE,
                            lld_status_t::STATE_STOPPING, lld_status_t::STATE_FAULT});
  m.segment_index = g.count(0, 5);
  m.progress = g.uniform(0, 10);
  m.cross_track_error = g.uniform(-0.1, 0.1);
  m.heading_error = g.uniform(-0.2, 0.2);
  m.v_cmd = g.uniform(0, 1);
  m.omega_cmd = g.uniform(-1, 1);
  m.predicted_end_utime = m.utime + g.count(0, 10'000'000);
  m.overruns = g.count(0, 3);
  m.period_jitter_ms = static_cast<float>(g.uniform(0, 2));
  return m;
}

template <>
region_name_request_t sample<region_name_request_t>(uint32_t variant)
{
  Gen g(variant, kSalt + 48);
  region_name_request_t m;
  m.utime = utime(g);
  m.region_id = g.count(1, 50);
  m.centroid = point(g);
  m.area = variant % 3 == 0 ? 0.0 : g.uniform(1, 200);
  m.description = variant % 2 ? g.word("room 12 m^2 with 2 gateways") : "";
  return m;
}

template <>
explorer_status_t sample<explorer_status_t>(uint32_t variant)
{
  Gen g(variant, kSalt + 49);
  explorer_status_t m;
  m.utime = utime(g);
  m.phase = g.pick<int8_t>({explorer_status_t::PHASE_WAITING, explorer_status_t::PHASE_EXPLORING,
                            explorer_status_t::PHASE_DONE});
  m.activity = g.word("frontier 2.1 m wide in region");
  m.current_region = g.count(0, 50);
  m.current_completeness = g.uniform(0, 1);
  m.regions = g.count(0, 40);
  m.complete_regions = g.count(0, m.regions);
  m.stack_pending = g.count(0, 10);
  m.stack_done = g.count(0, 30);
  m.stack_set_aside = g.count(0, 3);
  m.goals_sent = g.count(0, 100);
  m.goals_reached = g.count(0, m.goals_sent);
  m.goals_failed = m.goals_sent - m.goals_reached;
  const bool has_goal = variant % 3 != 0;
  m.goal_id = has_goal ? g.count(1, 100) : 0;
  m.goal_region = has_goal ? g.count(1, 50) : 0;
  if (has_goal) m.goal_map_point = point(g);
  else m.goal_map_point.x = m.goal_map_point.y = 0;
  return m;
}

template <>
fault_inject_t sample<fault_inject_t>(uint32_t variant)
{
  Gen g(variant, kSalt + 50);
  fault_inject_t m;
  m.utime = utime(g);
  m.target = g.word("proc");
  m.pid = variant % 2 ? 0 : g.count(2, 4'000'000);
  m.fault = fault_inject_t::FAULT_BUSY_LOOP;
  m.duration_ms = g.count(1, 5000);
  return m;
}

}  // namespace rgnav::testing
