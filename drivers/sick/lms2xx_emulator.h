// An LMS 291 on a pseudo-terminal, for tests, the simulator and manual runs. It speaks the
// telegram protocol from the device side: ACK/NAK, operating modes (installation with
// password, continuous output, values on request), baud changes, status, variant and
// configuration, reset with the power-on telegram; in continuous mode it sends 0xB0 telegrams
// at the real rate (one mirror rotation every 1/75 s: 181 beams ~75 Hz, 361 ~37.5 Hz) with
// distances from a ScanSource.
//
// The serial line is modelled: every write occupies the line for its wire time at the current
// baud (10 bits per byte) and reaches the pty when its last bit would have arrived; a scan
// that finishes while the line is still busy is skipped, as on the real device at low rates.
// The emulator reads the baud the host set on the slave side; while host and device disagree,
// what each sends is garbled for the other, so a driver that skips the baud handshake fails
// here as it would on hardware.
//
// Fault injection (thread-safe): garbage bytes, corrupted CRCs, a silent device, unplug
// (the port vanishes) and replug (a new pty behind the same symlink).
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "commands.h"
#include "pseudo_terminal.h"
#include "scan_source.h"
#include "telegram_parser.h"

namespace rgnav::drivers::sick {

struct EmulatorOptions
{
  std::string symlink_path;           // stable port name ("" = use the pts path)
  int initial_baud = 9600;            // rate after power-on
  Variant variant{180, 100};          // factory default 180° / 1°
  Units units = Units::kCentimetres;  // factory default of an LMS 291
  std::string password = kDefaultInstallationPassword;
  std::string software_version = "V02.10";
  std::string manufacturer = "SICK AG";
  std::string type = "LMS291;S05";    // text of the power-on telegram
  std::chrono::milliseconds reset_duration{300};  // reset until the power-on telegram
  double rotation_hz = 75.0;          // mirror rotations per second
};

class Lms2xxEmulator
{
 public:
  using Clock = std::chrono::steady_clock;

  struct SentScan
  {
    int64_t first_beam_utime = 0;  // [us] wall time the first beam was measured (truth)
    int64_t delivered_utime = 0;   // [us] wall time the last byte reached the pty
    int beams = 0;
    bool corrupted = false;
  };

  struct Stats
  {
    uint64_t requests = 0;         // well-formed requests handled
    uint64_t naks_sent = 0;        // requests with a broken frame/CRC
    uint64_t garbled_rx_bytes = 0; // received while the host's baud was wrong
    uint64_t scans_sent = 0;
    uint64_t scans_skipped = 0;    // finished while the line was busy
    uint64_t dropped_tx_bytes = 0; // nobody reading and the pty buffer full
    int baud = 0;
    bool streaming = false;
    bool plugged = false;
  };

  // Opens the pty and starts the device thread. Throws std::runtime_error if no pty.
  Lms2xxEmulator(EmulatorOptions options, std::shared_ptr<ScanSource> source);
  ~Lms2xxEmulator();
  Lms2xxEmulator(const Lms2xxEmulator&) = delete;
  Lms2xxEmulator& operator=(const Lms2xxEmulator&) = delete;

  // The path a driver opens: the symlink if configured, else the current pts.
  std::string port_path() const;

  // Sends these bytes on the line as soon as it is free (between telegrams).
  void inject_garbage(std::vector<uint8_t> bytes);
  // The next n measured-value telegrams go out with a wrong CRC.
  void corrupt_next_scans(int n);
  // A hung device: it keeps the port but sends nothing and ignores requests.
  void set_silent(bool silent);
  // The port vanishes (pty closed, symlink removed). The device keeps its state (baud,
  // mode), as an LMS does when only its USB-serial adapter is pulled.
  void unplug();
  // A new pty behind the same symlink. power_cycle also resets the device to power-on state
  // (initial baud, not streaming) and sends the power-on telegram.
  void replug(bool power_cycle = false);

  Stats stats() const;
  std::vector<SentScan> sent_scans() const;  // the most recent ones (bounded)
  int baud() const;

 private:
  struct Output
  {
    Clock::time_point due;  // when the last byte has crossed the line
    std::vector<uint8_t> bytes;
    std::optional<int> baud_after;  // a baud change takes effect after this reply
    std::optional<SentScan> scan;
  };

  void run();
  void wake();
  void apply_plug_requests(Clock::time_point now);
  void power_on_state();
  void handle_input(Clock::time_point now);
  void handle_request(const Telegram& t, Clock::time_point now);
  void schedule_scans(Clock::time_point now);
  void write_due_output(Clock::time_point now);
  void send(std::vector<uint8_t> bytes, Clock::time_point now, std::optional<int> baud_after = std::nullopt,
            std::optional<SentScan> scan = std::nullopt);
  void send_reply(const Telegram& reply, Clock::time_point now, std::optional<int> baud_after = std::nullopt);
  Clock::time_point scan_complete_time(int64_t index) const;
  Clock::duration wire_time(size_t bytes) const;
  int64_t to_wall_utime(Clock::time_point t) const;
  bool host_baud_matches() const;

  const EmulatorOptions options_;
  std::shared_ptr<ScanSource> source_;
  const Clock::time_point t0_;
  const int64_t wall_at_t0_us_;

  mutable std::mutex mutex_;  // guards everything below; the thread holds it except in poll()
  int wake_fd_ = -1;          // eventfd: API calls wake the thread's poll()
  bool stop_ = false;
  bool unplug_requested_ = false;
  std::optional<bool> replug_requested_;  // value = power_cycle
  PseudoTerminal pty_;
  std::vector<uint8_t> pending_garbage_;
  int corrupt_scans_ = 0;
  bool silent_ = false;
  Stats stats_;
  std::deque<SentScan> sent_;

  // Device state (thread only, but read by stats() under the mutex).
  int baud_ = 9600;
  bool streaming_ = false;
  bool installation_ = false;
  Variant variant_;
  ConfigBlock config_;
  std::optional<Clock::time_point> reset_done_at_;
  int64_t next_scan_index_ = 0;
  Clock::time_point line_free_at_{};
  std::deque<Output> out_;
  TelegramParser parser_{kAddressLms};

  std::thread thread_;
};

}  // namespace rgnav::drivers::sick
