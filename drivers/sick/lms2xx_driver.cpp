#include "lms2xx_driver.h"

#include <poll.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <thread>

#include "measured_values.h"

namespace rgnav::drivers::sick {

namespace {

constexpr int kBitsPerByte = 10;  // 8N1

int64_t wall_utime_now()
{
  return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}


}  // namespace

const char* to_string(Lms2xxDriver::State s)
{
  switch (s) {
    case Lms2xxDriver::State::kDisconnected: return "disconnected";
    case Lms2xxDriver::State::kDetecting: return "detecting baud";
    case Lms2xxDriver::State::kConfiguring: return "configuring";
    case Lms2xxDriver::State::kStreaming: return "streaming";
  }
  return "?";
}

void validate(const DriverOptions& o)
{
  auto bad = [](const std::string& what) { throw std::invalid_argument(what); };
  if (o.port.empty()) bad("port must not be empty");
  if (!baud_from_bits_per_second(o.initial_baud) || !serial_baud_supported(o.initial_baud))
    bad("initial_baud must be 9600, 19200, 38400 or 500000");
  if (!baud_from_bits_per_second(o.desired_baud) || !serial_baud_supported(o.desired_baud))
    bad("desired_baud must be 9600, 19200, 38400 or 500000");
  if (!variant_supported(o.variant))
    bad("angular range/resolution must be 180°/1°, 180°/0.5°, 100°/1°, 100°/0.5° or 100°/0.25°");
  if (o.units != Units::kMillimetres && o.units != Units::kCentimetres) bad("units must be mm or cm");
  if (o.password.size() != 8) bad("the installation password has 8 characters");
  if (o.request_tries < 1) bad("request_tries must be >= 1");
  if (o.rotation_hz <= 0) bad("rotation_hz must be > 0");
  // At the session rate a scan telegram takes this long on the wire; the silence timeout
  // must comfortably exceed the resulting scan period or a healthy device looks dead.
  const double wire_s = static_cast<double>(framed_size(2 * variant_beam_count(o.variant) + 4) * kBitsPerByte) /
                        o.desired_baud;
  const double rotation_s = 1.0 / o.rotation_hz;
  const double period_s = std::max(variant_rotations(o.variant) * rotation_s,
                                   std::ceil(wire_s / rotation_s) * rotation_s);
  if (std::chrono::duration<double>(o.silence_timeout).count() < 3.0 * period_s)
    bad("silence_timeout must be at least 3 scan periods (" + std::to_string(static_cast<int>(3000 * period_s)) +
        " ms at this baud and variant)");
}

Lms2xxDriver::Lms2xxDriver(DriverOptions options) : options_(std::move(options))
{
  validate(options_);
  // Try the configured power-on rate first, then the session rate (a device left streaming
  // by a previous run), then the rest.
  for (int b : {options_.initial_baud, options_.desired_baud, 9600, 38400, 19200, 500000})
    if (std::find(candidates_.begin(), candidates_.end(), b) == candidates_.end()) candidates_.push_back(b);
  next_attempt_ = Clock::now();
}

Lms2xxDriver::~Lms2xxDriver()
{
  // Leave the device quiet: a streaming LMS would otherwise flood the next opener.
  if (port_ && state_ == State::kStreaming) {
    const auto bytes = frame(request_mode(OperatingMode::kValuesOnRequest));
    port_->write_all(bytes.data(), bytes.size(), std::chrono::milliseconds(50));
  }
}

int Lms2xxDriver::fd() const { return port_ ? port_->fd() : -1; }

int Lms2xxDriver::current_baud() const { return port_ ? port_->baud() : 0; }

Lms2xxDriver::Clock::time_point Lms2xxDriver::next_deadline() const
{
  switch (state_) {
    case State::kDisconnected: return next_attempt_;
    case State::kDetecting:
    case State::kConfiguring: return deadline_;
    case State::kStreaming: return last_scan_at_ + options_.silence_timeout;
  }
  return Clock::now();
}

std::string Lms2xxDriver::status_text() const
{
  std::string s = to_string(state_);
  if (port_) s += " @" + std::to_string(port_->baud());
  s += ", scans " + std::to_string(stats_.scans) + ", crc errors " + std::to_string(stats_.crc_errors) +
       ", resyncs " + std::to_string(stats_.resyncs) + ", reconnects " + std::to_string(stats_.disconnects);
  if (stats_.rejected_scans) s += ", rejected " + std::to_string(stats_.rejected_scans);
  if (!last_error_.empty() && state_ != State::kStreaming) s += "; last error: " + last_error_;
  return s;
}

void Lms2xxDriver::set_port_baud(int bps)
{
  port_->set_baud(bps);
  parser_.reset();
}

void Lms2xxDriver::fail(const std::string& why, Clock::time_point now)
{
  if (state_ != State::kDisconnected) {
    spdlog::warn("LMS on {}: {} ({}); reconnecting in {} ms", options_.port, why, to_string(state_),
                 options_.reconnect_interval.count());
    ++stats_.disconnects;
  }
  last_error_ = why;
  port_.reset();
  parser_.reset();
  plan_.clear();
  state_ = State::kDisconnected;
  next_attempt_ = now + options_.reconnect_interval;
}

void Lms2xxDriver::try_connect(Clock::time_point now)
{
  try {
    port_ = std::make_unique<SerialPort>(options_.port, candidates_.front());
  } catch (const SerialError& e) {
    ++stats_.open_failures;
    if (!logged_open_failure_) spdlog::warn("{}; retrying every {} ms", e.what(), options_.reconnect_interval.count());
    logged_open_failure_ = true;
    last_error_ = e.what();
    next_attempt_ = now + options_.reconnect_interval;
    return;
  }
  logged_open_failure_ = false;
  parser_.reset();
  state_ = State::kDetecting;
  candidate_ = 0;
  start_probe(now);
}

void Lms2xxDriver::start_probe(Clock::time_point now)
{
  set_port_baud(candidates_[candidate_]);
  port_->flush();
  spdlog::debug("LMS on {}: probing at {} baud", options_.port, candidates_[candidate_]);
  const auto bytes = frame(request_mode(OperatingMode::kValuesOnRequest));
  if (!port_->write_all(bytes.data(), bytes.size())) return fail("write failed while probing", now);
  deadline_ = now + options_.detect_timeout;
}

void Lms2xxDriver::build_plan()
{
  plan_.clear();
  const int desired = options_.desired_baud;
  if (port_->baud() != desired) {
    plan_.push_back({"switch to " + std::to_string(desired) + " baud", request_baud(*baud_from_bits_per_second(desired)),
                     reply::kSwitchMode, options_.reply_timeout, [this, desired](const Reply& r) -> std::string {
                       const auto result = decode_mode_reply(r);
                       if (!result || *result != 0x00) return "baud change refused";
                       set_port_baud(desired);  // the LMS answered at the old rate and switched
                       return "";
                     }});
    plan_.push_back({"check link at " + std::to_string(desired) + " baud", request_mode(OperatingMode::kValuesOnRequest),
                     reply::kSwitchMode, options_.reply_timeout, [](const Reply& r) -> std::string {
                       const auto result = decode_mode_reply(r);
                       return result && *result == 0x00 ? "" : "no monitoring mode after the baud change";
                     }});
  }
  plan_.push_back({"set variant", request_variant(options_.variant), reply::kVariant, options_.reply_timeout,
                   [this](const Reply& r) -> std::string {
                     const auto v = decode_variant_reply(r);
                     if (!v) return "malformed variant reply";
                     if (!v->accepted || !(v->variant == options_.variant)) return "variant refused by the device";
                     return "";
                   }});
  plan_.push_back({"read configuration", request_config(), reply::kConfig, options_.reply_timeout,
                   [this](const Reply& r) -> std::string {
                     const auto c = decode_config_reply(r);
                     if (!c) return "malformed configuration reply";
                     device_config_ = *c;
                     if (c->units() == options_.units && c->measuring_mode() == kMeasuringMode8m80mFieldsDazzle) return "";
                     // Read-modify-write of the EEPROM block; only units and mode change.
                     ConfigBlock wanted = *c;
                     wanted.set_units(options_.units);
                     wanted.set_measuring_mode(kMeasuringMode8m80mFieldsDazzle);
                     std::vector<Step> more;
                     more.push_back({"enter installation mode", request_installation_mode(options_.password),
                                     reply::kSwitchMode, options_.reply_timeout, [](const Reply& rr) -> std::string {
                                       const auto m = decode_mode_reply(rr);
                                       if (!m) return "malformed mode reply";
                                       if (*m == 0x01) return "installation mode refused: wrong password";
                                       return *m == 0x00 ? "" : "installation mode refused";
                                     }});
                     more.push_back({"write configuration", request_set_config(wanted), reply::kSetConfig,
                                     options_.config_timeout, [wanted](const Reply& rr) -> std::string {
                                       const auto s = decode_set_config_reply(rr);
                                       if (!s) return "malformed configuration write reply";
                                       if (!s->accepted || !(s->config == wanted)) return "configuration refused";
                                       return "";
                                     }});
                     more.push_back({"leave installation mode", request_mode(OperatingMode::kValuesOnRequest),
                                     reply::kSwitchMode, options_.reply_timeout, [](const Reply& rr) -> std::string {
                                       const auto m = decode_mode_reply(rr);
                                       return m && *m == 0x00 ? "" : "monitoring mode refused";
                                     }});
                     // Insert right after the current step (which is still plan_.front()).
                     plan_.insert(plan_.begin() + 1, more.begin(), more.end());
                     spdlog::info("LMS on {}: configuring {} units", options_.port,
                                  options_.units == Units::kMillimetres ? "mm (8 m mode)" : "cm (80 m mode)");
                     return "";
                   }});
  plan_.push_back({"read status", request_status(), reply::kStatus, options_.reply_timeout,
                   [this](const Reply& r) -> std::string {
                     const auto s = decode_status_reply(r);
                     if (!s) return "malformed status reply";
                     if (s->device_status != 0) return "device reports an error";
                     if (!(s->variant == options_.variant) || s->units != options_.units)
                       return "status disagrees with the requested variant/units";
                     status_ = s;
                     return "";
                   }});
  plan_.push_back({"start continuous output", request_mode(OperatingMode::kContinuousAll), reply::kSwitchMode,
                   options_.reply_timeout, [](const Reply& r) -> std::string {
                     const auto m = decode_mode_reply(r);
                     return m && *m == 0x00 ? "" : "continuous mode refused";
                   }});
}

void Lms2xxDriver::start_step(Clock::time_point now)
{
  tries_left_ = options_.request_tries;
  send_current(now);
}

void Lms2xxDriver::send_current(Clock::time_point now)
{
  const Step& step = plan_.front();
  --tries_left_;
  const auto bytes = frame(step.request);
  if (!port_->write_all(bytes.data(), bytes.size())) return fail("write failed: " + step.what, now);
  deadline_ = now + step.timeout;
}

void Lms2xxDriver::on_timeout(Clock::time_point now)
{
  ++stats_.timeouts;
  if (state_ == State::kDetecting) {
    if (++candidate_ < candidates_.size()) return start_probe(now);
    return fail("no reply at any baud rate", now);
  }
  if (tries_left_ > 0) {
    spdlog::debug("LMS on {}: no reply to '{}', retrying", options_.port, plan_.front().what);
    return send_current(now);
  }
  fail("no reply to '" + plan_.front().what + "'", now);
}

void Lms2xxDriver::on_step_reply(const Reply& r, Clock::time_point now)
{
  Step step = plan_.front();
  if (r.command != step.expect) return;  // e.g. stray 0xB0 from a stream being stopped
  if (status_is_error(r.status)) return fail("device status error in reply to '" + step.what + "'", now);
  const std::string err = step.on_reply(r);
  if (!err.empty()) return fail(err, now);
  plan_.pop_front();
  if (!plan_.empty()) return start_step(now);
  state_ = State::kStreaming;
  last_scan_at_ = now;
  ++stats_.connects;
  last_error_.clear();
  spdlog::info("LMS on {}: streaming at {} baud, {}°/{}°, {}", options_.port, port_->baud(), options_.variant.angle_deg,
               options_.variant.resolution_cdeg / 100.0, options_.units == Units::kMillimetres ? "mm" : "cm");
}

void Lms2xxDriver::on_telegram(const ReceivedTelegram& rt, Clock::time_point now, std::vector<Lms2xxScan>* out)
{
  const auto reply = as_reply(rt.telegram);
  if (!reply) return;
  switch (state_) {
    case State::kDetecting:
      if (reply->command == reply::kSwitchMode) {
        const auto m = decode_mode_reply(*reply);
        if (m && *m == 0x00) {
          spdlog::info("LMS on {}: answers at {} baud", options_.port, port_->baud());
          state_ = State::kConfiguring;
          build_plan();
          start_step(now);
        }
      }
      return;
    case State::kConfiguring:
      on_step_reply(*reply, now);
      return;
    case State::kStreaming:
      if (reply->command != reply::kMeasuredValues) return;
      // Bytes read in the same chunk after this telegram crossed the line after it: at
      // least their wire time later. Without this, two scans read together (a late
      // wake-up) would get the same time.
      if (auto scan = to_scan(*reply, rt.rx_utime - static_cast<int64_t>(std::llround(
                                                      rt.trailing_bytes * kBitsPerByte * 1e6 / port_->baud())))) {
        last_scan_at_ = now;
        ++stats_.scans;
        out->push_back(std::move(*scan));
      } else {
        ++stats_.rejected_scans;
      }
      return;
    case State::kDisconnected:
      return;
  }
}

std::optional<Lms2xxScan> Lms2xxDriver::to_scan(const Reply& r, int64_t rx_utime)
{
  const auto m = decode_measured_values(r);
  if (!m || m->units != options_.units || m->partial_scan ||
      static_cast<int>(m->values.size()) != variant_beam_count(options_.variant))
    return std::nullopt;
  const double unit = units_in_metres(m->units);
  const int rotations = variant_rotations(options_.variant);
  const double rotation_s = 1.0 / options_.rotation_hz;
  Lms2xxScan out;
  out.rx_utime = rx_utime;
  out.status = m->status;
  sensors::LaserScan& s = out.scan;
  const double wire_s = static_cast<double>(framed_size(r.data.size() + 2) * kBitsPerByte) / port_->baud();
  const double sweep_s = ((rotations - 1) + options_.variant.angle_deg / 360.0) * rotation_s;
  s.utime = rx_utime - static_cast<int64_t>(std::llround((wire_s + sweep_s) * 1e6)) - options_.transmit_delay.count();
  s.angle_min = -options_.variant.angle_deg * M_PI / 360.0;
  s.angle_increment = options_.variant.resolution_cdeg * M_PI / 18000.0;
  s.range_min = unit;
  s.range_max = kNoReturnCode * unit;
  s.scan_time = rotations * rotation_s;
  s.ranges.resize(m->values.size());
  for (size_t i = 0; i < m->values.size(); ++i) {
    switch (classify_value(m->values[i])) {
      case ValueKind::kRange: s.ranges[i] = static_cast<float>(m->values[i] * unit); break;
      case ValueKind::kNoReturn: s.ranges[i] = static_cast<float>(s.range_max); break;
      case ValueKind::kInvalid: s.ranges[i] = 0.f; break;
    }
  }
  return out;
}

std::vector<Lms2xxScan> Lms2xxDriver::service()
{
  std::vector<Lms2xxScan> out;
  auto now = Clock::now();
  if (state_ == State::kDisconnected) {
    if (now >= next_attempt_) try_connect(now);
    return out;
  }
  uint8_t buf[4096];
  for (int chunk = 0; chunk < 64 && port_; ++chunk) {
    const auto r = port_->read_some(buf, sizeof buf);
    if (r.status == SerialPort::ReadStatus::kNoData) break;
    if (r.status == SerialPort::ReadStatus::kClosed) {
      fail("port closed by the device (unplugged?)", Clock::now());
      return out;
    }
    const int64_t rx_utime = wall_utime_now();
    now = Clock::now();
    const bool streaming = state_ == State::kStreaming;
    const ParserStats before = parser_.stats();
    auto parsed = parser_.feed(buf, r.size, rx_utime);
    if (streaming) {
      const ParserStats& after = parser_.stats();
      stats_.crc_errors += after.crc_errors - before.crc_errors;
      stats_.resyncs += after.resyncs - before.resyncs;
      stats_.skipped_bytes += after.skipped_bytes - before.skipped_bytes;
    }
    if (parsed.naks > 0) ++stats_.naks;
    if (parsed.naks > 0 && state_ == State::kConfiguring) {
      // The device got our request garbled: send it again at once if tries remain.
      if (tries_left_ > 0) send_current(now);
      else fail("request '" + plan_.front().what + "' refused with NAK", now);
    }
    for (const auto& rt : parsed.telegrams) {
      if (!port_) break;
      on_telegram(rt, now, &out);
    }
  }
  now = Clock::now();
  if (port_ && now >= next_deadline()) {
    if (state_ == State::kStreaming) fail("device silent for " + std::to_string(options_.silence_timeout.count()) + " ms", now);
    else on_timeout(now);
  }
  return out;
}

std::vector<Lms2xxScan> Lms2xxDriver::poll(std::chrono::milliseconds max_wait)
{
  const auto now = Clock::now();
  auto wait = std::chrono::duration_cast<std::chrono::milliseconds>(next_deadline() - now) + std::chrono::milliseconds(1);
  wait = std::clamp(wait, std::chrono::milliseconds(0), max_wait);
  if (port_) {
    pollfd p{port_->fd(), POLLIN, 0};
    ::poll(&p, 1, static_cast<int>(wait.count()));
  } else if (wait.count() > 0) {
    std::this_thread::sleep_for(wait);
  }
  return service();
}

}  // namespace rgnav::drivers::sick
