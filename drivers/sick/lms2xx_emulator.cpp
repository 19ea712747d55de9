#include "lms2xx_emulator.h"

#include <poll.h>
#include <sys/eventfd.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "measured_values.h"

namespace rgnav::drivers::sick {

namespace {

constexpr size_t kMaxSentScansKept = 4096;
constexpr int kBitsPerByte = 10;  // 8N1: start bit, 8 data bits, stop bit

int64_t wall_now_us()
{
  return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}

uint16_t to_raw_value(float metres, double unit_m)
{
  if (std::isnan(metres) || metres < 0.f) return 8191;  // invalid reading
  const double v = std::round(static_cast<double>(metres) / unit_m);
  if (!std::isfinite(v) || v > kMaxValidValue) return kNoReturnCode;
  return static_cast<uint16_t>(v);
}

}  // namespace

Lms2xxEmulator::Lms2xxEmulator(EmulatorOptions options, std::shared_ptr<ScanSource> source)
    : options_(std::move(options)),
      source_(std::move(source)),
      t0_(Clock::now()),
      wall_at_t0_us_(wall_now_us()),
      pty_(options_.symlink_path)
{
  if (!source_) throw std::invalid_argument("Lms2xxEmulator needs a ScanSource");
  if (!variant_supported(options_.variant)) throw std::invalid_argument("Lms2xxEmulator: unsupported variant");
  config_.set_measuring_mode(kMeasuringMode8m80mFieldsDazzle);
  config_.set_units(options_.units);
  // Blanking 0, sensitivity standard, availability 0, ... the rest of a factory block.
  variant_ = options_.variant;
  power_on_state();
  wake_fd_ = eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC);
  if (wake_fd_ < 0) throw std::runtime_error("eventfd failed");
  pty_.open();
  stats_.plugged = true;
  thread_ = std::thread([this] { run(); });
}

Lms2xxEmulator::~Lms2xxEmulator()
{
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake();
  if (thread_.joinable()) thread_.join();
  pty_.close();
  if (wake_fd_ >= 0) ::close(wake_fd_);
}

void Lms2xxEmulator::wake()
{
  const uint64_t one = 1;
  [[maybe_unused]] const ssize_t n = ::write(wake_fd_, &one, sizeof one);
}

void Lms2xxEmulator::power_on_state()
{
  baud_ = options_.initial_baud;
  streaming_ = false;
  installation_ = false;
  out_.clear();
  parser_.reset();
}

std::string Lms2xxEmulator::port_path() const
{
  std::lock_guard<std::mutex> lock(mutex_);
  return pty_.port_path();
}

void Lms2xxEmulator::inject_garbage(std::vector<uint8_t> bytes)
{
  {
    std::lock_guard<std::mutex> lock(mutex_);
    pending_garbage_.insert(pending_garbage_.end(), bytes.begin(), bytes.end());
  }
  wake();
}

void Lms2xxEmulator::corrupt_next_scans(int n)
{
  std::lock_guard<std::mutex> lock(mutex_);
  corrupt_scans_ += n;
}

void Lms2xxEmulator::set_silent(bool silent)
{
  std::lock_guard<std::mutex> lock(mutex_);
  silent_ = silent;
}

void Lms2xxEmulator::unplug()
{
  {
    std::lock_guard<std::mutex> lock(mutex_);
    unplug_requested_ = true;
    replug_requested_.reset();
  }
  wake();
  // Return once it is done, so a test can rely on the port being gone.
  for (;;) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (!unplug_requested_) return;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

void Lms2xxEmulator::replug(bool power_cycle)
{
  {
    std::lock_guard<std::mutex> lock(mutex_);
    replug_requested_ = power_cycle;
  }
  wake();
  for (;;) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (!replug_requested_) return;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

Lms2xxEmulator::Stats Lms2xxEmulator::stats() const
{
  std::lock_guard<std::mutex> lock(mutex_);
  Stats s = stats_;
  s.baud = baud_;
  s.streaming = streaming_;
  s.plugged = pty_.is_open();
  return s;
}

std::vector<Lms2xxEmulator::SentScan> Lms2xxEmulator::sent_scans() const
{
  std::lock_guard<std::mutex> lock(mutex_);
  return {sent_.begin(), sent_.end()};
}

int Lms2xxEmulator::baud() const
{
  std::lock_guard<std::mutex> lock(mutex_);
  return baud_;
}

Lms2xxEmulator::Clock::duration Lms2xxEmulator::wire_time(size_t bytes) const
{
  return std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(static_cast<double>(bytes * kBitsPerByte) / baud_));
}

int64_t Lms2xxEmulator::to_wall_utime(Clock::time_point t) const
{
  return wall_at_t0_us_ + std::chrono::duration_cast<std::chrono::microseconds>(t - t0_).count();
}

bool Lms2xxEmulator::host_baud_matches() const { return pty_.slave_baud() == baud_; }

// Scan j uses rotations r*j .. r*j + r-1 (r = 1, 2 or 4 interlaced rotations); it is complete
// when the mirror of its last rotation has swept the scan angle.
Lms2xxEmulator::Clock::time_point Lms2xxEmulator::scan_complete_time(int64_t index) const
{
  const int r = variant_rotations(variant_);
  const double rotations = static_cast<double>(r * index + r - 1) + variant_.angle_deg / 360.0;
  return t0_ + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(rotations / options_.rotation_hz));
}

void Lms2xxEmulator::send(std::vector<uint8_t> bytes, Clock::time_point now, std::optional<int> baud_after,
                          std::optional<SentScan> scan)
{
  const auto start = std::max(now, line_free_at_);
  line_free_at_ = start + wire_time(bytes.size());
  out_.push_back({line_free_at_, std::move(bytes), baud_after, scan});
}

void Lms2xxEmulator::send_reply(const Telegram& reply, Clock::time_point now, std::optional<int> baud_after)
{
  send({kAck}, now);
  send(frame(reply), now, baud_after);
}

void Lms2xxEmulator::run()
{
  std::unique_lock<std::mutex> lock(mutex_);
  while (!stop_) {
    auto now = Clock::now();
    apply_plug_requests(now);
    if (reset_done_at_ && now >= *reset_done_at_) {
      reset_done_at_.reset();
      power_on_state();
      line_free_at_ = now;
      const std::vector<uint8_t> text(options_.type.begin(), options_.type.end());
      send(frame(make_reply(reply::kPowerOn, text, 0x00)), now);
    }
    if (!pending_garbage_.empty()) {
      send(std::move(pending_garbage_), now);
      pending_garbage_.clear();
    }
    schedule_scans(now);
    write_due_output(now);

    // Sleep until the next output is due, the next scan completes, input arrives or an API
    // call wakes us.
    auto next = now + std::chrono::milliseconds(50);
    if (!out_.empty()) next = std::min(next, out_.front().due);
    if (streaming_ && !installation_) next = std::min(next, scan_complete_time(next_scan_index_));
    if (reset_done_at_) next = std::min(next, *reset_done_at_);
    const int wait_ms = static_cast<int>(std::max<int64_t>(
        0, std::chrono::duration_cast<std::chrono::microseconds>(next - now).count() + 999) / 1000);
    pollfd fds[2] = {{wake_fd_, POLLIN, 0}, {pty_.master_fd(), POLLIN, 0}};
    const nfds_t nfds = pty_.is_open() ? 2 : 1;
    lock.unlock();
    const int r = ::poll(fds, nfds, wait_ms);
    lock.lock();
    if (r > 0 && (fds[0].revents & POLLIN)) {
      uint64_t v;
      [[maybe_unused]] const ssize_t n = ::read(wake_fd_, &v, sizeof v);
    }
    if (r > 0 && nfds == 2 && (fds[1].revents & POLLIN)) handle_input(Clock::now());
  }
}

void Lms2xxEmulator::apply_plug_requests(Clock::time_point now)
{
  if (unplug_requested_) {
    pty_.close();
    out_.clear();
    parser_.reset();
    unplug_requested_ = false;
  }
  if (replug_requested_) {
    const bool power_cycle = *replug_requested_;
    pty_.open();
    line_free_at_ = now;
    if (power_cycle) {
      power_on_state();
      const std::vector<uint8_t> text(options_.type.begin(), options_.type.end());
      send(frame(make_reply(reply::kPowerOn, text, 0x00)), now);
    }
    replug_requested_.reset();
  }
}

void Lms2xxEmulator::handle_input(Clock::time_point now)
{
  uint8_t buf[1024];
  for (;;) {
    const ssize_t n = ::read(pty_.master_fd(), buf, sizeof buf);
    if (n <= 0) return;  // EAGAIN; EIO only while no slave is open (we hold one, so rare)
    if (silent_ || reset_done_at_) continue;
    if (!host_baud_matches()) {
      // At the wrong rate the UART only sees framing errors and noise.
      stats_.garbled_rx_bytes += static_cast<uint64_t>(n);
      continue;
    }
    const auto before = parser_.stats();
    auto parsed = parser_.feed(buf, static_cast<size_t>(n));
    const auto& after = parser_.stats();
    // A request whose frame is broken gets a NAK, as the LMS does.
    const uint64_t broken = (after.crc_errors - before.crc_errors);
    for (uint64_t i = 0; i < broken; ++i) {
      send({kNak}, now);
      ++stats_.naks_sent;
    }
    for (const auto& rt : parsed.telegrams) {
      ++stats_.requests;
      handle_request(rt.telegram, now);
    }
  }
}

void Lms2xxEmulator::handle_request(const Telegram& t, Clock::time_point now)
{
  const auto& p = t.payload;
  const uint8_t status = 0x00;
  switch (t.command()) {
    case cmd::kReset:
      send_reply(make_reply(reply::kResetAck, {}, status), now);
      streaming_ = false;
      reset_done_at_ = now + options_.reset_duration;
      return;
    case cmd::kSwitchMode: {
      if (p.size() < 2) break;
      const uint8_t mode = p[1];
      if (mode == static_cast<uint8_t>(OperatingMode::kInstallation)) {
        const std::string given(p.begin() + 2, p.end());
        const bool ok = given == options_.password;
        if (ok) {
          installation_ = true;
          streaming_ = false;
        }
        send_reply(encode_mode_reply(ok ? 0x00 : 0x01, status), now);
        return;
      }
      if (p.size() != 2) break;
      if (mode == static_cast<uint8_t>(OperatingMode::kContinuousAll)) {
        installation_ = false;
        if (!streaming_) {
          streaming_ = true;
          // The first scan is the next one whose measurement starts after this request.
          const int r = variant_rotations(variant_);
          const double rot = std::chrono::duration<double>(now - t0_).count() * options_.rotation_hz;
          next_scan_index_ = static_cast<int64_t>(std::ceil(rot / r));
        }
        send_reply(encode_mode_reply(0x00, status), now);
        return;
      }
      if (mode == static_cast<uint8_t>(OperatingMode::kValuesOnRequest)) {
        installation_ = false;
        streaming_ = false;
        send_reply(encode_mode_reply(0x00, status), now);
        return;
      }
      for (Baud b : {Baud::k9600, Baud::k19200, Baud::k38400, Baud::k500000}) {
        if (mode == static_cast<uint8_t>(b)) {
          // Acknowledged at the old rate; the new one applies once the reply is out.
          send_reply(encode_mode_reply(0x00, status), now, baud_bits_per_second(b));
          return;
        }
      }
      send_reply(encode_mode_reply(0x01, status), now);
      return;
    }
    case cmd::kRequestStatus: {
      StatusReport s;
      s.software_version = options_.software_version;
      s.operating_mode = installation_ ? 0x00 : (streaming_ ? 0x24 : 0x25);
      s.device_status = 0;
      s.manufacturer = options_.manufacturer;
      s.measuring_mode = config_.measuring_mode();
      s.variant = variant_;
      s.units = config_.units();
      send_reply(encode_status_reply(s, status), now);
      return;
    }
    case cmd::kSetVariant: {
      if (p.size() != 5) break;
      Variant v{get_u16(&p[1]), get_u16(&p[3])};
      VariantReply reply;
      reply.accepted = variant_supported(v);
      if (reply.accepted) {
        variant_ = v;
        streaming_ = false;
      }
      reply.variant = variant_;
      send_reply(encode_variant_reply(reply, status), now);
      return;
    }
    case cmd::kRequestConfig:
      if (p.size() != 1) break;
      send_reply(encode_config_reply(config_, status), now);
      return;
    case cmd::kSetConfig: {
      if (p.size() != 1 + ConfigBlock::kSize) break;
      SetConfigReply reply;
      reply.accepted = installation_;  // the EEPROM is writable in installation mode only
      if (reply.accepted) config_.bytes.assign(p.begin() + 1, p.end());
      reply.config = config_;
      send_reply(encode_set_config_reply(reply, status), now);
      return;
    }
    default:
      break;
  }
  send_reply(make_reply(reply::kIncorrectCommand, {}, status), now);
}

void Lms2xxEmulator::schedule_scans(Clock::time_point now)
{
  if (!streaming_ || installation_) return;
  const int beams = variant_beam_count(variant_);
  const int r = variant_rotations(variant_);
  const double rotation_s = 1.0 / options_.rotation_hz;
  while (scan_complete_time(next_scan_index_) <= now) {
    const auto done = scan_complete_time(next_scan_index_);
    const int64_t index = next_scan_index_++;
    if (!pty_.is_open() || silent_) continue;  // the device scans on, nobody hears it
    if (line_free_at_ > done) {
      ++stats_.scans_skipped;
      continue;
    }
    const auto first_beam = t0_ + std::chrono::duration_cast<Clock::duration>(
                                      std::chrono::duration<double>(static_cast<double>(r * index) * rotation_s));
    ScanRequest req;
    req.utime = to_wall_utime(first_beam);
    req.angle_min_rad = -variant_.angle_deg * M_PI / 360.0;
    req.angle_increment_rad = variant_.resolution_cdeg * M_PI / 18000.0;
    req.count = beams;
    req.scan_time_s = std::chrono::duration<double>(done - first_beam).count();
    const auto ranges = source_->ranges(req);
    MeasuredValues m;
    m.units = config_.units();
    m.values.resize(static_cast<size_t>(beams), kNoReturnCode);
    const double unit = units_in_metres(m.units);
    for (size_t i = 0; i < m.values.size() && i < ranges.size(); ++i) m.values[i] = to_raw_value(ranges[i], unit);
    auto bytes = frame(encode_measured_values(m));
    SentScan truth;
    truth.first_beam_utime = req.utime;
    truth.beams = beams;
    if (corrupt_scans_ > 0) {
      --corrupt_scans_;
      bytes.back() ^= 0xFF;
      truth.corrupted = true;
    }
    send(std::move(bytes), done, std::nullopt, truth);
  }
}

void Lms2xxEmulator::write_due_output(Clock::time_point now)
{
  while (!out_.empty() && out_.front().due <= now) {
    Output o = std::move(out_.front());
    out_.pop_front();
    if (pty_.is_open() && !silent_) {
      if (!host_baud_matches())
        for (auto& b : o.bytes) b ^= 0x5A;  // what a UART at another rate makes of it
      const ssize_t n = ::write(pty_.master_fd(), o.bytes.data(), o.bytes.size());
      if (n < static_cast<ssize_t>(o.bytes.size()))
        stats_.dropped_tx_bytes += o.bytes.size() - static_cast<size_t>(std::max<ssize_t>(n, 0));
      if (o.scan) {
        o.scan->delivered_utime = wall_now_us();
        ++stats_.scans_sent;
        sent_.push_back(*o.scan);
        if (sent_.size() > kMaxSentScansKept) sent_.pop_front();
      }
    }
    if (o.baud_after) baud_ = *o.baud_after;
  }
}

}  // namespace rgnav::drivers::sick
