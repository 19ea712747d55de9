#include "importers/lcm_log_io.h"

#include <lcm/lcm-cpp.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "bus/typed.h"
#include "msg/conversions.h"
#include "rgnav/laser_scan_t.hpp"
#include "rgnav/odometry_t.hpp"

namespace rgnav::importers {
namespace {

// An event on disk: sync word, event number, timestamp, channel length, data length (lcm's
// eventlog format), then the channel name and the data.
constexpr long kEventHeaderBytes = 4 + 8 + 8 + 4 + 4;

// A log scan as the laser would have sent it: numbered in log order, named by its channel.
laser_scan_t to_message(const sensors::LaserScan& s, int64_t scan_id, const std::string& sensor)
{
  laser_scan_t m = msg::to_msg(s);
  m.scan_id = scan_id;
  m.sensor = sensor;
  return m;
}

class Writer
{
 public:
  explicit Writer(const std::string& path) : file_(path, "w")
  {
    if (!file_.good()) throw std::runtime_error("cannot write " + path);
  }
  template <class T>
  void write(const std::string& channel, const T& msg)
  {
    std::vector<uint8_t> buf;
    std::string why;
    if (!bus::encode(msg, &buf, &why)) throw std::runtime_error("invalid " + channel + " message: " + why);
    lcm::LogEvent ev;
    ev.eventnum = eventnum_++;
    ev.timestamp = msg.utime;
    ev.channel = channel;
    ev.datalen = static_cast<int32_t>(buf.size());
    ev.data = buf.data();
    if (file_.writeEvent(&ev) != 0) throw std::runtime_error("write failed on " + channel);
  }

 private:
  lcm::LogFile file_;
  int64_t eventnum_ = 0;
};

// An odometry_t at a pose record: its time, the pose (heading wrapped into [-pi, pi]), status OK;
// no velocities or distance.
odometry_t pose_message(const PoseRecord& p, int64_t seq)
{
  odometry_t m{};
  m.utime = p.utime;
  m.seq = seq;
  m.odom_from_base.x = p.x;
  m.odom_from_base.y = p.y;
  m.odom_from_base.theta = std::remainder(p.theta, 2.0 * M_PI);
  m.status = odometry_t::STATUS_OK;
  return m;
}

}  // namespace

WriteSummary write_lcm_log(const ImportedLog& log, const std::string& path, const LogChannels& ch)
{
  Writer w(path);
  WriteSummary sum;
  int64_t scan_id = 0, rear_id = 0, odom_seq = 0;
  double distance = 0.0;
  const PoseRecord* prev = nullptr;
  for (const auto& e : log.events) {
    switch (e.kind) {
      case LogEvent::Kind::kScan:
        w.write(ch.laser_front, to_message(log.scans[e.index], ++scan_id, "laser_front"));
        ++sum.scans;
        break;
      case LogEvent::Kind::kRearScan:
        w.write(ch.laser_rear, to_message(log.rear_scans[e.index], ++rear_id, "laser_rear"));
        ++sum.rear_scans;
        break;
      case LogEvent::Kind::kOdometry: {
        const PoseRecord& p = log.odometry[e.index];
        odometry_t m = pose_message(p, ++odom_seq);
        if (prev) {
          const double step = std::hypot(p.x - prev->x, p.y - prev->y);
          distance += step;
          const double dt = 1e-6 * static_cast<double>(p.utime - prev->utime);
          if (dt > 1e-4) {
            m.v = step / dt;
            m.omega = std::remainder(p.theta - prev->theta, 2.0 * M_PI) / dt;
          }
        }
        m.distance = distance;
        prev = &p;
        w.write(ch.odometry, m);
        ++sum.odometry;
        break;
      }
      case LogEvent::Kind::kReference: {
        // seq: the scan this reference pose belongs to.
        w.write(ch.reference, pose_message(log.reference[e.index], scan_id));
        ++sum.reference;
        break;
      }
    }
  }
  return sum;
}

LogFraming for_each_lcm_event(const std::string& path, const std::function<void(const lcm::LogEvent&, int64_t)>& on_event)
{
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) throw std::runtime_error(path + ": cannot read LCM log: " + ec.message());
  if (size == 0) throw std::runtime_error(path + ": empty file, not an LCM log");
  lcm::LogFile file(path, "r");
  if (!file.good()) throw std::runtime_error("cannot read LCM log " + path);
  LogFraming framing;
  FILE* fp = file.getFilePtr();
  long good_end = 0;  // file position after the last complete event
  for (const lcm::LogEvent* ev = file.readNextEvent(); ev; ev = file.readNextEvent()) {
    // lcm's reader may skip bytes up to the next sync word without a word: an event that does
    // not begin where the last one ended had damage (or, before the first, no log at all) in front.
    const long end = fp ? std::ftell(fp) : 0;
    const long start = end - kEventHeaderBytes - static_cast<long>(ev->channel.size()) - static_cast<long>(ev->datalen);
    if (fp && start != good_end) {
      if (framing.events == 0)
        throw std::runtime_error(path + ": not an LCM log (no LCM event at its start; the first sync word is at byte " +
                                 std::to_string(start) + ")");
      framing.issues.push_back({framing.events + 1, std::to_string(start - good_end) + " damaged bytes skipped before this event"});
    }
    ++framing.events;
    good_end = end;
    on_event(*ev, framing.events);
  }
  if (framing.events == 0)
    throw std::runtime_error(path + ": not an LCM log (no complete LCM event in its " + std::to_string(size) + " bytes)");
  // lcm's reader returns null both at the end and at a damaged event; a damaged tail shows as
  // bytes after the last complete event.
  framing.good_bytes = good_end;
  if (fp) {
    std::fseek(fp, 0, SEEK_END);
    if (std::ftell(fp) > good_end) {
      framing.truncated = true;
      framing.issues.push_back({framing.events + 1, "damaged or truncated event at the end of the log (read up to byte " +
                                                        std::to_string(good_end) + ")"});
    }
  }
  return framing;
}

ImportedLog read_lcm_log(const std::string& path, const LogChannels& ch)
{
  ImportedLog log;
  log.format = "lcm";
  const LogFraming framing = for_each_lcm_event(path, [&](const lcm::LogEvent& ev, int64_t n) {
    const auto* data = static_cast<const uint8_t*>(ev.data);
    const size_t size = static_cast<size_t>(ev.datalen);
    std::string why;
    if (ev.channel == ch.laser_front || ev.channel == ch.laser_rear) {
      laser_scan_t m;
      if (!bus::decode(data, size, &m, &why)) {
        log.issues.push_back({n, ev.channel + ": " + why});
        return;
      }
      if (ev.channel == ch.laser_front)
        log.add_scan(msg::to_laser_scan(m));
      else
        log.add_rear_scan(msg::to_laser_scan(m));
    } else if (ev.channel == ch.odometry || ev.channel == ch.reference) {
      odometry_t m;
      if (!bus::decode(data, size, &m, &why)) {
        log.issues.push_back({n, ev.channel + ": " + why});
        return;
      }
      PoseRecord p{m.utime, m.seq, m.odom_from_base.x, m.odom_from_base.y, m.odom_from_base.theta};
      if (ev.channel == ch.odometry)
        log.add_odometry(p);
      else
        log.add_reference(p);
    }
  });
  log.issues.insert(log.issues.end(), framing.issues.begin(), framing.issues.end());
  std::stable_sort(log.issues.begin(), log.issues.end(), [](const ImportIssue& a, const ImportIssue& b) { return a.line < b.line; });
  log.lines = framing.events;
  log.truncated = framing.truncated;
  return log;
}

}  // namespace rgnav::importers
