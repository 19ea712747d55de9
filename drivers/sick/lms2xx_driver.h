// The host side of an LMS 2xx on a serial port, as a non-blocking state machine (no threads,
// no LCM): the caller waits on fd() and calls service() when it is readable and at
// next_deadline(). It
//   1. opens the port and finds the device's current rate: at each candidate baud it asks for
//      "values on request" (0x20 0x25, which also stops a stream left running by an earlier
//      session) until a 0xA0 reply arrives;
//   2. switches to the desired baud (0x20 0x40/41/42/48, acknowledged at the old rate, then
//      the host port follows) and checks the new rate with another request;
//   3. sets the variant (0x3B), reads the configuration (0x74) and, if the units or the
//      measuring mode differ, writes it (installation mode with password, 0x77, back to
//      monitoring), reads the status (0x31) to confirm;
//   4. starts continuous output (0x20 0x24) and turns each 0xB0 telegram into a LaserScan.
// Every request is retried on NAK or timeout; any failure, a vanished port or a silent
// device closes the port and starts over after the reconnect interval.
//
// Timestamps: the LMS starts sending a scan right after its last beam, so the first beam was
// measured at
//   t_first = t_rx − wire_time(telegram at the current baud) − transmit_delay − sweep_time
// where t_rx is the wall time the read() returning the telegram's last byte completed (less
// the wire time of any bytes that read returned after it),
// wire_time = bytes × 10 bits / baud (8N1), transmit_delay a configurable fixed device
// latency (0 by default), and sweep_time = ((r − 1) + angle/360°) / 75 Hz the time from first
// to last beam (r interlaced rotations: 1 at 1°, 2 at 0.5°, 4 at 0.25°).
#pragma once

#include <chrono>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "commands.h"
#include "sensors/laser_scan.h"
#include "serial_port.h"
#include "telegram_parser.h"

namespace rgnav::drivers::sick {

struct DriverOptions
{
  std::string port = "/dev/ttyS0";
  int initial_baud = 9600;      // rate tried first (the LMS's power-on rate)
  int desired_baud = 500000;    // session rate
  Variant variant{180, 100};
  Units units = Units::kMillimetres;  // mm: 8 m mode; cm: 80 m mode
  std::string password = kDefaultInstallationPassword;
  std::chrono::milliseconds reply_timeout{1000};   // per request
  std::chrono::milliseconds detect_timeout{400};   // per baud candidate
  std::chrono::milliseconds config_timeout{5000};  // EEPROM writes are slow
  int request_tries = 3;
  std::chrono::milliseconds silence_timeout{1000}; // streaming, no scan for this long: reconnect
  std::chrono::milliseconds reconnect_interval{1000};
  std::chrono::microseconds transmit_delay{0};     // last beam → first byte on the line
  double rotation_hz = 75.0;
};

// Throws std::invalid_argument naming the bad field.
void validate(const DriverOptions& o);

// One scan from the device: the common scan (utime: estimated acquisition time of beam 0, wall
// time; range_min one unit, 0 meaning "invalid reading"; range_max 8183 units, "no return";
// sensor and scan_id are the node's to set) and what only this driver knows.
struct Lms2xxScan
{
  sensors::LaserScan scan;
  int64_t rx_utime = 0;  // [us] when its last byte was read
  uint8_t status = 0;    // telegram status byte
};

struct DriverStats
{
  uint64_t scans = 0;
  uint64_t connects = 0;          // times streaming started
  uint64_t disconnects = 0;       // port vanished, device silent, or setup failed
  uint64_t open_failures = 0;
  // Link errors while streaming (setup at a wrong baud produces plenty, not counted here).
  uint64_t crc_errors = 0;
  uint64_t resyncs = 0;
  uint64_t skipped_bytes = 0;
  uint64_t rejected_scans = 0;    // good CRC but wrong count/units for the configured mode
  uint64_t naks = 0;
  uint64_t timeouts = 0;
};

class Lms2xxDriver
{
 public:
  using Clock = std::chrono::steady_clock;
  enum class State { kDisconnected, kDetecting, kConfiguring, kStreaming };

  explicit Lms2xxDriver(DriverOptions options);
  ~Lms2xxDriver();

  // The open port's fd, or -1 (nothing to wait on; call service() at next_deadline()).
  int fd() const;
  // Reads whatever is available, runs due timeouts, returns completed scans.
  std::vector<Lms2xxScan> service();
  // Convenience for loops that own no poller (tests, tools): waits up to max_wait for input
  // or the next deadline, then service().
  std::vector<Lms2xxScan> poll(std::chrono::milliseconds max_wait);
  Clock::time_point next_deadline() const;

  State state() const { return state_; }
  const DriverStats& stats() const { return stats_; }
  int current_baud() const;
  const std::string& last_error() const { return last_error_; }
  const std::optional<StatusReport>& device_status() const { return status_; }
  // One line for the heartbeat: state, rate, counters, last error.
  std::string status_text() const;
  const DriverOptions& options() const { return options_; }

 private:
  struct Step
  {
    std::string what;
    Telegram request;
    uint8_t expect = 0;
    std::chrono::milliseconds timeout{0};
    // Returns an error text, or "" if the reply is acceptable.
    std::function<std::string(const Reply&)> on_reply;
  };

  void try_connect(Clock::time_point now);
  void start_probe(Clock::time_point now);
  void build_plan();
  void start_step(Clock::time_point now);
  void send_current(Clock::time_point now);
  void fail(const std::string& why, Clock::time_point now);
  void on_timeout(Clock::time_point now);
  void on_telegram(const ReceivedTelegram& rt, Clock::time_point now, std::vector<Lms2xxScan>* out);
  void on_step_reply(const Reply& r, Clock::time_point now);
  std::optional<Lms2xxScan> to_scan(const Reply& r, int64_t rx_utime);
  void set_port_baud(int bps);

  const DriverOptions options_;
  std::unique_ptr<SerialPort> port_;
  TelegramParser parser_{kAddressHost};
  State state_ = State::kDisconnected;
  Clock::time_point next_attempt_{};  // kDisconnected: when to try opening again
  Clock::time_point deadline_{};      // kDetecting / kConfiguring: reply deadline
  Clock::time_point last_scan_at_{};  // kStreaming: silence detection
  std::vector<int> candidates_;
  size_t candidate_ = 0;
  std::deque<Step> plan_;
  int tries_left_ = 0;
  ConfigBlock device_config_;
  std::optional<StatusReport> status_;
  std::string last_error_;
  bool logged_open_failure_ = false;
  DriverStats stats_;
};

const char* to_string(Lms2xxDriver::State s);

}  // namespace rgnav::drivers::sick
