#include "sim_runs.h"

#include <chrono>
#include <map>

#include <spdlog/spdlog.h>
#include <cmath>

#include "sim/lms2xx_model.h"
#include "sim/rng.h"
#include "sim/tour_planner.h"
#include "sim/waypoint_follower.h"

namespace rgnav::gateway_detector::tools {

namespace {

int class_of(sim::GatewayClass c)
{
  switch (c) {
    case sim::GatewayClass::kXCrossing: return kX;
    case sim::GatewayClass::kTJunction: return kT;
    case sim::GatewayClass::kLTJunction: return kLT;
    case sim::GatewayClass::kRTJunction: return kRT;
    case sim::GatewayClass::kLTurn: return kLTurn;
    case sim::GatewayClass::kRTurn: return kRTurn;
    case sim::GatewayClass::kDeadEnd: return kDeadEnd;
    default: return -1;
  }
}

bool same_direction(double a, double b) { return std::fabs(geometry::normalize_angle(a - b)) < 0.3; }

geometry::Pose2 to_pose(const sim::Pose2& p) { return geometry::Pose2(p.x, p.y, p.theta); }

double elapsed_ms(std::chrono::steady_clock::time_point t0)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

bool near_any(const Vec2& p, const std::vector<sim::Vec2>& pts, double tol)
{
  for (const auto& q : pts)
    if ((p - q).norm() < tol) return true;
  return false;
}

// Does the recorded VLM describe ground-truth gateway g?
bool matches(const FinishedSequence& f, const sim::Gateway& g, double tol)
{
  if (g.points.size() == 4) {
    for (const auto& p : f.points)
      if (!near_any(p, g.points, tol)) return false;
    return true;
  }
  // A dead end: its ground truth is the end wall; the VLM's front corners must lie on it.
  return near_any(f.points[1], g.points, tol) && near_any(f.points[2], g.points, tol);
}

bool segments_cross(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d)
{
  auto cross = [](const Vec2& u, const Vec2& v) { return u.x() * v.y() - u.y() * v.x(); };
  const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a), d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
  return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0));
}

}  // namespace

int crossing_class_for(const sim::Gateway& g, double heading)
{
  const int cls = class_of(g.cls);
  if (cls < 0) return -1;
  std::vector<double> open;
  if (cls == kX) {
    open = {0.0, M_PI / 2, M_PI, -M_PI / 2};
  } else {
    if (!g.heading) return -1;
    const double h = *g.heading;
    open.push_back(h + M_PI);
    const double dirs[3] = {h + M_PI / 2, h, h - M_PI / 2};
    for (int s = 0; s < 3; ++s)
      if (expects_open(cls, s)) open.push_back(dirs[s]);
  }
  auto is_open = [&](double d) {
    for (double o : open)
      if (same_direction(o, d)) return true;
    return false;
  };
  if (!is_open(heading + M_PI)) return -1;
  const bool l = is_open(heading + M_PI / 2), f = is_open(heading), r = is_open(heading - M_PI / 2);
  for (int c = 0; c < kNumCrossingClasses; ++c)
    if (expects_open(c, kLeftSector) == l && expects_open(c, kFrontSector) == f && expects_open(c, kRightSector) == r) return c;
  return -1;
}

std::vector<Approach> approaches(const sim::World& world)
{
  std::vector<Approach> out;
  for (size_t i = 0; i < world.gateways.size(); ++i) {
    const auto& g = world.gateways[i];
    if (class_of(g.cls) < 0) continue;
    Approach a;
    a.gateway = i;
    a.center = sim::Vec2::Zero();
    for (const auto& p : g.points) a.center += p;
    a.center /= static_cast<double>(g.points.size());
    a.width = (g.points[1] - g.points[0]).norm();
    const std::vector<double> headings =
        g.cls == sim::GatewayClass::kDeadEnd ? std::vector<double>{g.heading.value_or(0.0)} : std::vector<double>{0.0, M_PI / 2, M_PI, -M_PI / 2};
    for (double h : headings) {
      a.cls = crossing_class_for(g, h);
      a.heading = h;
      if (a.cls >= 0) out.push_back(a);
    }
  }
  return out;
}

std::vector<LabelledSequence> record_sequences(const sim::World& world, const DetectorOptions& options,
                                               const RecordOptions& ro, RecordStats* stats)
{
  std::vector<LabelledSequence> out;
  sim::SimulatorOptions so;
  so.laser_enabled = false;  // scans are measured below at the processing rate
  const sim::Simulator probe(world, so);
  const double body = so.robot.radius + 0.1;
  const auto list = approaches(world);
  for (size_t ai = 0; ai < list.size(); ++ai) {
    const Approach& a = list[ai];
    const Vec2 u(std::cos(a.heading), std::sin(a.heading)), n(-u.y(), u.x());
    const bool dead_end = a.cls == kDeadEnd;
    const Vec2 goal = dead_end ? Vec2(a.center - (a.width / 2 + 0.5) * u) : a.center;
    // The longest free straight approach up to approach_length.
    double length = ro.approach_length;
    auto clear = [&](double len) {
      for (double s = 0; s <= len - 0.5; s += 0.25)
        if (probe.clearance(a.center - (len - s) * u, body) < body) return false;
      return true;
    };
    while (length > 3.0 && !clear(length)) length -= 0.5;
    if (length <= 3.0) continue;

    for (int r = 0; r < ro.repetitions; ++r) {
      const uint64_t run_seed = ro.seed * 1'000'003ull + ai * 1000ull + static_cast<uint64_t>(r);
      sim::Rng rng = sim::Rng::derive(run_seed, 11);
      const double off = (2.0 * rng.uniform() - 1.0) * ro.lateral_fraction * a.width;
      const Vec2 start = a.center - length * u + off * n;
      sim::World w = world;
      w.start = {start.x(), start.y(), a.heading + rng.normal(ro.heading_noise)};
      so.seed = run_seed;
      sim::Simulator sim(std::move(w), so);
      sim::Lms2xxModel laser(so.laser, sim::Rng::derive(run_seed, 12));
      sim::FollowerOptions fo;
      fo.v = ro.speed;
      sim::WaypointFollower follower({goal + off * n}, [&sim] { return sim.truth(); }, fo);
      sim.set_command_source(&follower);
      GatewayDetector det(options);
      const geometry::Pose2 mount(so.laser.mount_x, so.laser.mount_y, so.laser.mount_yaw);
      const auto dt = std::chrono::microseconds(static_cast<int64_t>(1e6 / ro.scan_hz));
      const double limit = length / ro.speed + 15.0;
      int64_t id = 0;
      int kept = 0;
      while (!follower.done() && sim.time_s() < limit) {
        sim.step(dt);
        PosedScan ps;
        // The scan as measured, its header in double, not rounded to float as on LASER_FRONT:
        // max-range readings (8.183 m as float, 8.1829996) lie below range_max (8.183) and so
        // count as hits here, not as "no return". Kept as it was so the figures stay.
        ps.scan = laser.measure(sim.scene(), sim.doors_open(), sim.people(), sim.truth(), sim.now_utime(), ++id);
        ps.map_from_base = to_pose(sim.truth());
        ps.base_from_laser = mount;
        const auto t0 = std::chrono::steady_clock::now();
        det.process(ps);
        if (stats) stats->scan_ms.push_back(elapsed_ms(t0));
        for (auto& f : det.take_finished_sequences()) {
          spdlog::debug("{} {} approach {} run {}: track {} group {} entered {} n {} d {:.2f}->{:.2f} pts ({:.2f},{:.2f}) ({:.2f},{:.2f}) ({:.2f},{:.2f}) ({:.2f},{:.2f}) match {}",
                        world.gateways[a.gateway].name, crossing_class_name(a.cls), ai, r, f.track_id, f.group, f.entered, f.sequence.size(),
                        f.sequence.empty() ? 0.0 : f.sequence.front().distance, f.sequence.empty() ? 0.0 : f.sequence.back().distance,
                        f.points[0].x(), f.points[0].y(), f.points[1].x(), f.points[1].y(), f.points[2].x(), f.points[2].y(),
                        f.points[3].x(), f.points[3].y(), matches(f, world.gateways[a.gateway], ro.match_fraction * a.width));
          if (f.sequence.size() < 2) continue;
          if (!matches(f, world.gateways[a.gateway], ro.match_fraction * a.width)) {
            if (stats) ++stats->sequences_unmatched;
            continue;
          }
          if (ro.complete_only && !f.entered) {
            if (stats) {
              ++stats->sequences_corrupted;
              stats->corrupted_lengths.push_back(static_cast<int>(f.sequence.size()));
              stats->corrupted_last_distance.push_back(f.sequence.back().distance);
            }
            continue;
          }
          if (stats) {
            stats->kept_first_distance.push_back(f.sequence.front().distance);
            stats->kept_lengths.push_back(static_cast<int>(f.sequence.size()));
          }
          ++kept;
          out.push_back({world.name, world.gateways[a.gateway].name, a.cls, r, static_cast<int>(ai), f.group, std::move(f.sequence)});
        }
      }
      if (stats) {
        ++stats->runs;
        if (kept == 0) {
          ++stats->runs_without_sequence;
          ++stats->runs_without_sequence_by_approach[world.gateways[a.gateway].name + " " + crossing_class_name(a.cls)];
        }
      }
    }
  }
  return out;
}

DoorEvaluation evaluate_doors(const sim::World& world, const DetectorOptions& options, double scan_hz, uint64_t seed,
                              std::vector<double>* scan_ms, const DoorVision* vision)
{
  DoorEvaluation ev;
  sim::SimulatorOptions so;
  so.seed = seed;
  so.laser_enabled = false;
  const sim::Tour tour = sim::plan_tour(world, so.robot);
  ev.tour_length = tour.length;
  spdlog::info("tour of {}: {:.0f} m, {} waypoints, {} regions visited, {} unreachable, collision free: {}", world.name,
               tour.length, tour.waypoints.size(), tour.visited.size(), tour.unreachable.size(), tour.collision_free);
  for (const auto& w : tour.waypoints) spdlog::debug("waypoint {:.2f} {:.2f}", w.x(), w.y());
  // The waypoint follower stands in for navigation and cannot avoid people: the tour is driven
  // without them (the hallway worlds' strong clutter keeps its people).
  sim::World quiet = world;
  quiet.people.clear();
  sim::Simulator sim(quiet, so);
  sim::Lms2xxModel laser(so.laser, sim::Rng::derive(seed, 12));
  sim::WaypointFollower follower(tour.waypoints, [&sim] { return sim.truth(); });
  sim.set_command_source(&follower);
  GatewayDetector det(options);
  GatewayDetector det_vision(options);  // the same scans, and the camera's rectangles
  std::map<int64_t, bool> vision_tracks;  // track -> classified a door
  const geometry::Pose2 mount(so.laser.mount_x, so.laser.mount_y, so.laser.mount_yaw);

  std::vector<size_t> doors;
  for (size_t i = 0; i < world.gateways.size(); ++i)
    if (world.gateways[i].cls == sim::GatewayClass::kDoor && world.gateways[i].points.size() == 2) doors.push_back(i);
  auto door_of = [&](const std::vector<Vec2>& pts) -> int {
    for (size_t k = 0; k < doors.size(); ++k) {
      const auto& g = world.gateways[doors[k]].points;
      const double tol = 0.3;
      if (((pts[0] - g[0]).norm() < tol && (pts[1] - g[1]).norm() < tol) || ((pts[0] - g[1]).norm() < tol && (pts[1] - g[0]).norm() < tol))
        return static_cast<int>(k);
    }
    return -1;
  };
  std::vector<double> last_report(doors.size(), -1e9);  // sim time of the newest approached passage per door
  std::vector<double> last_traversal(doors.size(), -1e9);
  std::vector<double> last_door_class(doors.size(), -1e9);  // sim time the vision detector last called it a door
  double next_frame = 0.0;
  const auto dt = std::chrono::microseconds(static_cast<int64_t>(1e6 / scan_hz));
  const double limit = tour.length / 0.3 + 120.0;
  Vec2 prev(sim.truth().x, sim.truth().y);
  int64_t id = 0;
  while (!follower.done() && sim.time_s() < limit) {
    sim.step(dt);
    PosedScan ps;
    ps.scan = laser.measure(  // double header, as above: max-range readings count as hits
        sim.scene(), sim.doors_open(), sim.people(), sim.truth(), sim.now_utime(), ++id);
    ps.map_from_base = to_pose(sim.truth());
    ps.base_from_laser = mount;
    const auto t0 = std::chrono::steady_clock::now();
    const auto out = det.process(ps);
    if (scan_ms) scan_ms->push_back(elapsed_ms(t0));
    if (vision && vision->see) {
      if (sim.time_s() >= next_frame) {
        next_frame = sim.time_s() + 1.0 / vision->rate_hz;
        ++ev.vision_frames;
        det_vision.add_rectangles(sim.now_utime(), ps.map_from_base, vision->see(sim.truth(), sim.doors_open(), ev.vision_frames));
      }
      for (const auto& e : det_vision.process(ps).events) {
        if (e.gateway_class != kOutNarrowPassage && e.gateway_class != kOutDoor) continue;
        bool& called_door = vision_tracks[e.track_id];
        const int d = door_of(e.gateway_points);
        if (e.gateway_class == kOutDoor && !called_door) {
          called_door = true;
          ++ev.vision_doors_classified;
          if (d >= 0) ++ev.vision_classified_on_doors;
        }
        if (e.gateway_class == kOutDoor && d >= 0) last_door_class[static_cast<size_t>(d)] = sim.time_s();
      }
    }
    for (const auto& e : out.events) {
      if (e.kind != EventKind::kApproached || (e.gateway_class != kOutNarrowPassage && e.gateway_class != kOutDoor)) continue;
      ++ev.passages_reported;
      const int d = door_of(e.gateway_points);
      if (d < 0)
        spdlog::debug("t={:.1f} passage not on a door: ({:.2f},{:.2f}) ({:.2f},{:.2f}) robot ({:.2f},{:.2f})", sim.time_s(),
                      e.gateway_points[0].x(), e.gateway_points[0].y(), e.gateway_points[1].x(), e.gateway_points[1].y(),
                      sim.truth().x, sim.truth().y);
      if (d >= 0) {
        ++ev.passages_on_doors;
        last_report[static_cast<size_t>(d)] = sim.time_s();
      }
    }
    const Vec2 cur(sim.truth().x, sim.truth().y);
    for (size_t k = 0; k < doors.size(); ++k) {
      const auto& g = world.gateways[doors[k]].points;
      if (!segments_cross(prev, cur, g[0], g[1])) continue;
      ++ev.doors_traversed;
      // Detected if a matching passage was reported in the approach to this traversal (after
      // the previous traversal of the same door, within 20 s).
      if (last_report[k] > last_traversal[k] && sim.time_s() - last_report[k] < 20.0) ++ev.doors_detected;
      if (last_door_class[k] > last_traversal[k] && sim.time_s() - last_door_class[k] < 20.0) ++ev.vision_doors_detected;
      else {
        ev.missed.push_back(world.gateways[doors[k]].name);
        spdlog::debug("t={:.1f} MISSED traversal of {} heading {:.2f}", sim.time_s(), world.gateways[doors[k]].name, sim.truth().theta);
      }
      last_traversal[k] = sim.time_s();
    }
    prev = cur;
  }
  spdlog::info("tour ended at {:.0f} s: waypoint {} of {}, {} collisions", sim.time_s(), follower.next_index(),
               tour.waypoints.size(), sim.collisions());
  return ev;
}

}  // namespace rgnav::gateway_detector::tools
