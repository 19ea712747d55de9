#include "localizer/localizer_node.h"

#include <spdlog/fmt/fmt.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>

#include "config/config.h"
#include "geometry/pose_track.h"
#include "msg/conversions.h"
#include "rgmap/rgmap_conversions.h"
#include "rgmap/saved_map.h"
#include "rgnav/gateway_passed_t.hpp"
#include "rgnav/heartbeat_t.hpp"
#include "rgnav/region_pose_t.hpp"

namespace rgnav::localizer {

namespace {

constexpr double kDeg = M_PI / 180.0;
// Scans waiting for the odometry sample after them (the laser runs at up to 75 Hz, odometry at
// 50 Hz: one or two wait at a time).
constexpr size_t kMaxPendingScans = 32;
// utime and seq beyond this are refused, so that differences of them cannot overflow.
constexpr int64_t kMaxStamp = int64_t{1} << 62;
bool stamp_ok(int64_t v) { return v > 0 && v < kMaxStamp; }
// Wall time without a scan used (laser or odometry gone) after which the status says so.
constexpr std::chrono::seconds kScansStaleAfter{1};

double ms_since(std::chrono::steady_clock::time_point t0)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

LocalizerNode::LocalizerNode(runtime::Node& node, const LocalizerNodeOptions& options, LocalizerFiles files)
    : node_(node),
      options_(options),
      files_(std::move(files)),
      loc_(options.localizer),
      max_scan_age_us_(static_cast<int64_t>(std::llround(options.max_scan_age * 1e6))),
      max_odometry_gap_us_(std::max<int64_t>(1'000'000, 2 * max_scan_age_us_)),
      persist_period_us_(static_cast<int64_t>(std::llround(options.persist_period * 1e6)))
{
  loc_.set_progress([this] { node_.note_progress(); });
  if (!files_.state_file.empty()) {
    std::string problem;
    saved_ = load_estimate(files_.state_file, &problem);
    if (saved_)
      spdlog::info("saved estimate in {}: region {} at ({:.2f}, {:.2f}, {:.1f} deg), map version {}", files_.state_file,
                   saved_->region, saved_->region_from_base.x(), saved_->region_from_base.y(),
                   saved_->region_from_base.theta() / kDeg, saved_->map_version);
    else if (!problem.empty()) {
      // Kept for a look, out of the way of the next save: global localization instead.
      const std::string aside = files_.state_file + ".damaged";
      std::error_code ec;
      std::filesystem::rename(files_.state_file, aside, ec);
      spdlog::error("saved estimate not used ({}), moved to {}: global localization with the first scan", problem, aside);
    }
    else
      spdlog::info("no saved estimate in {}: global localization with the first scan", files_.state_file);
  }
  if (!files_.map.empty()) {
    take_map(rgmap::load_map_flag(files_.map), files_.map);
  } else {
    spdlog::info("no saved map given (--map): waiting for {}", options_.channels.rg_map);
  }

  const auto& ch = options_.channels;
  node_.subscribe<rg_map_t>(ch.rg_map, [this](const rg_map_t& m) { on_map(m); });
  node_.subscribe<odometry_t>(ch.odometry, [this](const odometry_t& m) { on_odometry(m); });
  node_.subscribe<laser_scan_t>(ch.laser, [this](const laser_scan_t& m) { on_scan(m); });
  node_.subscribe<localize_request_t>(ch.request, [this](const localize_request_t& m) { on_request(m); });
  node_.every(std::chrono::milliseconds(500), [this] { report(); });
  report();
}

LocalizerNode::~LocalizerNode() { save(true); }

void LocalizerNode::on_map(const rg_map_t& m)
{
  if (m.version == loc_.maps().version()) return;   // the kernel republishes its map at 1 Hz
  rgmap::RgMap map;
  try {
    map = rgmap::from_msg(m);
  } catch (const std::exception& e) {
    return node_.drops().drop(options_.channels.rg_map, std::string("RG map refused: ") + e.what());
  }
  take_map(map, options_.channels.rg_map);
}

void LocalizerNode::take_map(const rgmap::RgMap& map, const std::string& source)
{
  const bool first = loc_.maps().version() < 0;
  const auto t0 = std::chrono::steady_clock::now();
  loc_.set_map(map);
  const auto log = first ? spdlog::level::info : spdlog::level::debug;
  spdlog::log(log, "map version {} from {}: {} regions ({:.1f} MB of fields) in {:.0f} ms", map.version, source,
              loc_.maps().regions().size(), static_cast<double>(loc_.maps().bytes()) / 1e6, ms_since(t0));
  if (loc_.maps().empty()) spdlog::warn("map version {} from {} has no region to localize in", map.version, source);
  if (saved_ && !loc_.maps().empty()) {
    const SavedEstimate s = *saved_;
    saved_.reset();
    if (loc_.resume(s.region, s.region_from_base)) {
      resumed_from_ = s;
      spdlog::info("resuming from the saved estimate: region {} at ({:.2f}, {:.2f}, {:.1f} deg)", loc_.estimate().region,
                   s.region_from_base.x(), s.region_from_base.y(), s.region_from_base.theta() / kDeg);
    } else {
      spdlog::warn("the saved estimate's region {} is not in map version {}: global localization", s.region, map.version);
    }
  }
  report();
}

void LocalizerNode::on_odometry(const odometry_t& m)
{
  const auto& ch = options_.channels;
  if (!stamp_ok(m.utime) || !(m.seq >= 0 && m.seq < kMaxStamp))
    return node_.drops().drop(ch.odometry, "odometry utime or seq out of range");
  const OdometrySample sample{m.utime, msg::to_pose2(m.odom_from_base)};
  // The base driver publishes at its own rate and repeats the last sample's stamp, under a newer
  // sequence number, when the drives' next sample is late (a loaded host): nothing new and
  // nothing wrong, so neither a drop nor, while a sample is held, a sample that fails to continue it.
  if (held_ && m.utime == held_->sample.utime && m.seq > held_->seq) {
    held_->seq = m.seq;
    return;
  }
  if (!held_ && !odometry_.empty() && m.utime == odometry_.back().utime && m.seq > last_odometry_seq_) {
    last_odometry_seq_ = m.seq;
    return;
  }
  // A sample that broke the sequence or the time is believed once the next one continues from
  // it: a restarted driver (sequence from the start, new frame) or a real pause in the time,
  // but not a stray or corrupted sample, which would otherwise hold all odometry after it.
  if (held_) {
    const HeldOdometry h = *held_;
    held_.reset();
    const bool continues = m.seq > h.seq && m.seq - h.seq <= 3 && m.utime > h.sample.utime &&
                           m.utime - h.sample.utime <= max_odometry_gap_us_ && (!h.restart || m.seq < last_odometry_seq_);
    if (continues) {
      if (h.restart) {
        odometry_restarted(fmt::format("odometry sequence went back ({} -> {})", last_odometry_seq_, h.seq));
      } else {
        spdlog::warn("odometry time jumped ahead by {:.2f} s", static_cast<double>(h.sample.utime - odometry_.back().utime) * 1e-6);
      }
      accept_odometry(h.seq, h.sample);
      accept_odometry(m.seq, sample);
      return;
    }
    node_.drops().drop(ch.odometry, fmt::format("odometry sample {} was not continued by the next one (stray)", h.seq));
  }
  const bool seq_back = last_odometry_seq_ >= 0 && m.seq < last_odometry_seq_;
  if (!odometry_.empty() && !seq_back && m.utime <= odometry_.back().utime)
    return node_.drops().drop(ch.odometry, "odometry not newer than the last sample (duplicate or out of order)");
  if (seq_back || (!odometry_.empty() && m.utime - odometry_.back().utime > max_odometry_gap_us_)) {
    held_ = HeldOdometry{m.seq, sample, seq_back};
    return;
  }
  accept_odometry(m.seq, sample);
}

void LocalizerNode::accept_odometry(int64_t seq, const OdometrySample& sample)
{
  last_odometry_seq_ = seq;
  odometry_.push_back(sample);
  // A few seconds are plenty: scans are used as soon as the sample after them is there.
  const int64_t keep = std::max<int64_t>(2'000'000, 4 * max_scan_age_us_);
  while (odometry_.size() > 2 && odometry_[1].utime < sample.utime - keep) odometry_.pop_front();
  while (!pending_.empty() && pending_.front().utime <= sample.utime) {
    const sensors::LaserScan scan = std::move(pending_.front());
    pending_.pop_front();
    if (const auto odom = odometry_at(scan.utime)) process(scan, *odom);
    else drop_scan(scan, "the odometry around it is more than max_scan_age_s away");
  }
}

void LocalizerNode::odometry_restarted(const std::string& why)
{
  // A restarted base driver starts a new odometry frame: the filter's last odometry pose means
  // nothing in it. Tracking goes on from the estimate, re-anchored at the next scan.
  spdlog::warn("{}: new odometry frame, re-anchoring the localizer", why);
  odometry_.clear();
  while (!pending_.empty()) {
    drop_scan(pending_.front(), "odometry restarted while it waited");
    pending_.pop_front();
  }
  loc_.reset_odometry();
  report();
}

std::optional<geometry::Pose2> LocalizerNode::odometry_at(int64_t utime) const
{
  return geometry::bracketed_at(odometry_, utime, max_scan_age_us_, [](const OdometrySample& s) { return s.odom_from_base; });
}

void LocalizerNode::drop_scan(const sensors::LaserScan& scan, const std::string& why)
{
  node_.drops().drop(options_.channels.laser, fmt::format("scan {}: {}", scan.scan_id, why));
}

void LocalizerNode::on_scan(const laser_scan_t& m)
{
  if (!stamp_ok(m.utime)) return node_.drops().drop(options_.channels.laser, "scan utime out of range");
  sensors::LaserScan scan = msg::to_laser_scan(m);
  if (scan.utime <= last_scan_utime_) return drop_scan(scan, "not newer than the last scan");
  if (odometry_.empty()) return drop_scan(scan, "no odometry yet on " + options_.channels.odometry);
  // Waiting scans whose odometry would now come later than max_scan_age never will in time.
  while (!pending_.empty() && scan.utime - pending_.front().utime > max_scan_age_us_) {
    drop_scan(pending_.front(), "no odometry after it within max_scan_age_s");
    pending_.pop_front();
  }
  const int64_t newest = odometry_.back().utime;
  if (scan.utime > newest) {
    if (scan.utime - newest > max_scan_age_us_)
      return drop_scan(scan, fmt::format("the newest odometry is {:.2f} s older (max_scan_age_s {:.2f})",
                                         static_cast<double>(scan.utime - newest) * 1e-6, options_.max_scan_age));
    last_scan_utime_ = scan.utime;
    pending_.push_back(std::move(scan));
    if (pending_.size() > kMaxPendingScans) {
      drop_scan(pending_.front(), "too many scans waiting for odometry");
      pending_.pop_front();
    }
    return;
  }
  const auto odom = odometry_at(scan.utime);
  if (!odom) return drop_scan(scan, "no odometry on both sides of it within max_scan_age_s");
  process(scan, *odom);
}

void LocalizerNode::process(const sensors::LaserScan& scan, const geometry::Pose2& odom_from_base)
{
  last_scan_utime_ = std::max(last_scan_utime_, scan.utime);
  last_scan_used_ = std::chrono::steady_clock::now();
  const Mode before = loc_.mode();
  const auto t0 = std::chrono::steady_clock::now();
  const bool updated = loc_.update(scan, odom_from_base);
  const double ms = ms_since(t0);
  if (ms > 200.0) spdlog::info("scan {} ({}) took {:.0f} ms", scan.scan_id, to_string(before), ms);
  if (loc_.take_kidnap_flag())
    spdlog::warn("kidnapped at scan {}: the estimate stopped explaining the scans; global localization ({} so far)",
                 scan.scan_id, loc_.stats().kidnaps);
  if (updated && loc_.estimate().valid) publish_estimate();
  if (updated) save(false);
  for (const GatewayPassed& g : loc_.take_gateway_events()) {
    gateway_passed_t out;
    out.utime = g.utime;
    out.gateway_id = g.gateway;
    out.from_region = g.from_region;
    out.to_region = g.to_region;
    out.region_from_base = msg::to_msg(g.region_from_base);
    out.distance_past = g.distance_past;
    spdlog::info("passed gateway {}: region {} -> {}", g.gateway, g.from_region, g.to_region);
    node_.publish(options_.channels.gateway_passed, out);
  }
  report();
}

void LocalizerNode::publish_estimate()
{
  const Estimate& e = loc_.estimate();
  region_pose_t m;
  m.utime = e.utime;
  m.scan_id = e.scan_id;
  m.region_id = e.region;
  m.region_from_base = msg::to_msg(e.region_from_base);
  m.map_from_base = msg::to_msg(e.map_from_base);
  m.odom_from_base = msg::to_msg(e.odom_from_base);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) m.covariance[3 * r + c] = e.covariance(r, c);
  // localizer.h: confidence is 0 while the filter has not converged.
  m.confidence = e.converged ? static_cast<float>(std::clamp(e.confidence, 0.0, 1.0)) : 0.f;
  node_.publish(options_.channels.pose, m);
}

void LocalizerNode::on_request(const localize_request_t& m)
{
  const std::string& ch = options_.channels.request;
  if (m.mode == localize_request_t::MODE_GLOBAL) {
    spdlog::info("localize request: forget the pose, global localization from the next scan");
    loc_.start_global();
    saved_.reset();
    // A restart must not resume the pose the operator just called wrong.
    if (!files_.state_file.empty()) {
      std::error_code ec;
      std::filesystem::remove(files_.state_file, ec);
    }
    return report();
  }
  if (loc_.maps().empty()) return node_.drops().drop(ch, "pose request before there is a map");
  const int64_t region = m.region_id != 0 ? loc_.maps().resolve(m.region_id) : loc_.maps().find_named(m.region_name);
  if (region == 0)
    return node_.drops().drop(ch, m.region_id != 0 ? fmt::format("pose request for unknown region {}", m.region_id)
                                                   : fmt::format("pose request for unknown region '{}'", m.region_name));
  const geometry::Pose2 pose = msg::to_pose2(m.region_from_base);
  const double sigma_xy = m.sigma_xy > 0 ? m.sigma_xy : options_.localizer.initial_xy;
  const double sigma_theta = m.sigma_theta > 0 ? m.sigma_theta : options_.localizer.initial_theta_deg * kDeg;
  if (!loc_.set_pose(region, pose, sigma_xy, sigma_theta))
    return node_.drops().drop(ch, fmt::format("pose request for region {} refused", region));
  saved_.reset();
  const RegionModel* r = loc_.maps().region(region);
  spdlog::info("localize request: region {}{} at ({:.2f}, {:.2f}, {:.1f} deg), sigma {:.2f} m / {:.1f} deg", region,
               r && !r->name.empty() ? " '" + r->name + "'" : std::string(), pose.x(), pose.y(), pose.theta() / kDeg,
               sigma_xy, sigma_theta / kDeg);
  if (r && !r->is_free(pose.translation())) spdlog::info("the requested pose is outside region {}'s freespace", region);
  report();
}

void LocalizerNode::save(bool now)
{
  if (files_.state_file.empty()) return;
  const Estimate& e = loc_.estimate();
  if (loc_.mode() != Mode::kTracking || !e.valid || !e.converged || e.utime == last_saved_utime_) return;
  // Due every persist_period of scan time (a log replayed from its start again: at once).
  const bool due = last_saved_utime_ == 0 || e.utime < last_saved_utime_ || e.utime - last_saved_utime_ >= persist_period_us_;
  if (!now && !due) return;
  try {
    save_estimate(files_.state_file, SavedEstimate{e.utime, e.region, e.region_from_base, e.map_from_base, loc_.maps().version()});
    last_saved_utime_ = e.utime;
    ++saves_;
    if (save_failed_) spdlog::info("saving the estimate to {} works again", files_.state_file);
    save_failed_ = false;
  } catch (const std::exception& ex) {
    if (!save_failed_) spdlog::error("saving the estimate failed: {}", ex.what());
    save_failed_ = true;
  }
}

void LocalizerNode::report()
{
  const Mode mode = loc_.mode();
  const Estimate& e = loc_.estimate();
  std::string text = fmt::format("{}: {} particles, confidence {:.2f}, {} kidnaps", to_string(mode), loc_.particles().size(),
                                 e.valid && e.converged ? e.confidence : 0.0, loc_.stats().kidnaps);
  if (mode == Mode::kTracking && e.valid) text += fmt::format(", region {}", e.region);
  if (save_failed_) text += "; saving the estimate fails";
  // The runtime's own "inputs stale" is overridden by this status: say it here.
  const auto since_scan = std::chrono::steady_clock::now() - last_scan_used_;
  const bool stale = since_scan > kScansStaleAfter;
  if (stale)
    text += last_scan_used_ == std::chrono::steady_clock::time_point{}
                ? "; no scan used yet"
                : fmt::format("; no scan used for {} s", std::chrono::duration_cast<std::chrono::seconds>(since_scan).count());
  if (mode != reported_mode_) spdlog::info("{} (was: {})", to_string(mode), to_string(reported_mode_));
  if (mode == reported_mode_ && text == reported_text_) return;
  reported_mode_ = mode;
  reported_text_ = text;
  const bool fine = mode == Mode::kTracking && !save_failed_ && !stale;
  node_.set_status(fine ? heartbeat_t::STATE_RUNNING : heartbeat_t::STATE_DEGRADED, text);
}

}  // namespace rgnav::localizer
