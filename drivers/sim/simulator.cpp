#include "sim/simulator.h"

#include <algorithm>
#include <cmath>

namespace rgnav::sim {

namespace {

// Salts give each random consumer its own stream, so adding noise to one never shifts another.
constexpr uint64_t kLaserSalt = 1;
constexpr uint64_t kOdometrySalt = 2;
constexpr uint64_t kPeopleSalt = 4;  // 3: the protocol laser (protocol_hardware.cpp)

int64_t event_time_us(int64_t k, double rate_hz) { return std::llround(static_cast<double>(k) * 1e6 / rate_hz); }

}  // namespace

Simulator::Simulator(World world, const SimulatorOptions& options)
    : world_(std::move(world)),
      options_(options),
      scene_(world_),
      drive_(options.drive),
      odometry_(options.odometry, Rng::derive(options.seed, kOdometrySalt)),
      laser_(options.laser, Rng::derive(options.seed, kLaserSalt)),
      people_(world_.people, Rng::derive(options.seed, kPeopleSalt)),
      door_open_(world_.doors.size(), 1),
      truth_(world_.start)
{
  update_doors();
}

void Simulator::update_doors()
{
  for (size_t i = 0; i < world_.doors.size(); ++i) door_open_[i] = world_.doors[i].open_at(time_s()) ? 1 : 0;
}

double Simulator::clearance(const Vec2& p, double search, std::string* what) const
{
  const HeightBand band{options_.robot.ground_clearance, options_.robot.height};
  const Clearance c = scene_.clearance(p, search, band, door_open_);
  double best = c.distance;
  if (what && c.owner >= 0) *what = scene_.owner_names()[static_cast<size_t>(c.owner)];
  const auto discs = options_.people_block_robot ? people_.discs() : std::vector<Circle>{};
  for (size_t i = 0; i < discs.size(); ++i) {
    const double d = (discs[i].center - p).norm() - discs[i].radius;
    if (d < best && d <= search) {
      best = d;
      if (what) *what = "person " + world_.people[i].name;
    }
  }
  return best;
}

StepOutput Simulator::step(std::chrono::microseconds dt)
{
  StepOutput out;
  const int64_t end = now_us_ + std::max<int64_t>(0, dt.count());
  while (now_us_ < end) {
    const int64_t next_scan = options_.laser_enabled ? event_time_us(scans_done_ + 1, options_.laser.rate_hz()) : INT64_MAX;
    const int64_t next_odom = event_time_us(odometry_done_ + 1, options_.odometry_hz);
    const int64_t t = std::min({end, now_us_ + options_.physics_step.count(), next_scan, next_odom});
    physics(t, &out);
    if (now_us_ == next_scan) {
      ++scans_done_;
      out.scans.push_back(laser_.measure(scene_, door_open_, people_.discs(), truth_, now_utime(), scans_done_));
    }
    if (now_us_ == next_odom) {
      ++odometry_done_;
      OdometrySample s;
      s.utime = now_utime();
      s.seq = odometry_done_;
      s.odom_from_base = odometry_.pose();
      s.v = drive_.v();
      s.omega = drive_.omega();
      s.distance = odometry_.distance();
      s.world_from_base = truth_;
      s.commanded = commanded_;
      s.true_v = true_v_;
      s.true_omega = true_omega_;
      s.true_distance = true_distance_;
      out.odometry.push_back(s);
    }
  }
  return out;
}

void Simulator::physics(int64_t t_end_us, StepOutput* out)
{
  const double dt = static_cast<double>(t_end_us - now_us_) * 1e-6;
  const std::optional<DriveCommand> told = source_ ? source_->command_at(now_utime()) : std::nullopt;
  commanded_ = told.has_value();
  const DriveCommand cmd = told.value_or(DriveCommand{});
  BaseMotion motion = drive_.step(cmd, dt, source_ && source_->ramped_by_drives());
  const double r = options_.robot.radius;
  auto body_clearance = [&](const Pose2& p) { return clearance({p.x, p.y}, r + 0.05); };
  Pose2 next = apply_motion(truth_, motion.ds, motion.dtheta);
  const double before = body_clearance(truth_);
  double after = body_clearance(next);
  // Blocked: the body would overlap something and get deeper into it. Moving away from an
  // obstacle already touched is allowed, so the robot can always back out.
  if (after < r && after < before) {
    double lo = 0.0, hi = 1.0;
    for (int i = 0; i < 16; ++i) {  // contact to within 1/65536 of the step
      const double mid = 0.5 * (lo + hi);
      const Pose2 p = apply_motion(truth_, mid * motion.ds, motion.dtheta);
      const double c = body_clearance(p);
      if (c < r && c < before) hi = mid; else lo = mid;
    }
    motion.ds *= lo;
    next = apply_motion(truth_, motion.ds, motion.dtheta);
    drive_.stop_translation();
    if (!in_contact_) {
      ++collision_count_;
      CollisionEvent ev;
      ev.utime = options_.start_utime + t_end_us;
      ev.world_from_base = next;
      clearance({next.x, next.y}, r + 0.05, &ev.with);
      out->collisions.push_back(ev);
    }
    in_contact_ = true;
  } else if (std::fabs(motion.ds) > 1e-9) {
    in_contact_ = false;
  }
  truth_ = next;
  true_distance_ += std::fabs(motion.ds);
  true_v_ = dt > 0.0 ? motion.ds / dt : 0.0;
  true_omega_ = dt > 0.0 ? motion.dtheta / dt : 0.0;
  odometry_.integrate(motion);
  const HeightBand band{options_.robot.ground_clearance, options_.robot.height};
  people_.advance(dt,
                  options_.people_block_robot ? std::optional<Circle>(Circle{Vec2(truth_.x, truth_.y), r}) : std::nullopt,
                  [&](const Vec2& p, double search) { return scene_.clearance(p, search, band, door_open_).distance; });
  now_us_ = t_end_us;
  update_doors();
}

}  // namespace rgnav::sim
