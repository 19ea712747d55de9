// The driver library against the emulated LMS 291 over a real pseudo-terminal, in one
// process: init sequence, baud switch, units configuration, continuous stream with the
// right ranges and timestamps, garbage, a corrupted CRC, an unplugged and a silent device.
#include <gtest/gtest.h>

#include <cmath>
#include <thread>

#include "driver_test_support.h"
#include "lms2xx_emulator.h"
#include "serial_port.h"
#include "synthetic_room.h"

namespace rgnav::drivers::sick {
namespace {

using namespace std::chrono_literals;
using testing::fast_options;
using testing::run_until;
using testing::unique_port_name;

SyntheticRoomOptions room_with_door()
{
  SyntheticRoomOptions r;
  r.front_m = 3.0;
  r.left_m = 1.5;
  r.right_m = 2.5;
  r.door_y_min_m = -0.5;
  r.door_y_max_m = 0.5;
  return r;
}

EmulatorOptions with_link(EmulatorOptions eo)
{
  eo.symlink_path = unique_port_name("drv");
  return eo;
}

struct Rig
{
  explicit Rig(EmulatorOptions eo = {}, SyntheticRoomOptions ro = room_with_door())
      : room(std::make_shared<SyntheticRoom>(ro)), emulator(with_link(std::move(eo)), room)
  {
  }
  std::shared_ptr<SyntheticRoom> room;
  Lms2xxEmulator emulator;
};

void expect_ranges_match_room(const sensors::LaserScan& s, const SyntheticRoom& room, double step)
{
  ASSERT_GT(s.ranges.size(), 0u);
  int doorway = 0;
  for (size_t i = 0; i < s.ranges.size(); ++i) {
    const double bearing = s.angle_min + static_cast<double>(i) * s.angle_increment;
    const double truth = room.range_at(bearing);
    if (!std::isfinite(truth) || truth >= s.range_max) {
      EXPECT_EQ(s.ranges[i], static_cast<float>(s.range_max)) << "beam " << i;
      ++doorway;
    } else {
      EXPECT_NEAR(s.ranges[i], truth, step / 2 + 1e-4) << "beam " << i;
    }
  }
  EXPECT_GT(doorway, 0) << "the doorway should give some no-return beams";
}

TEST(Lms2xxDriver, InitSwitchesBaudSetsUnitsAndStreamsCorrectRanges)
{
  Rig rig;  // powers on at 9600 baud in cm
  Lms2xxDriver driver(fast_options(rig.emulator.port_path()));
  std::vector<Lms2xxScan> scans;
  ASSERT_TRUE(run_until(driver, &scans, [&] { return scans.size() >= 30; })) << driver.status_text();

  EXPECT_EQ(driver.state(), Lms2xxDriver::State::kStreaming);
  EXPECT_EQ(driver.current_baud(), 500000);
  EXPECT_EQ(rig.emulator.baud(), 500000);
  ASSERT_TRUE(driver.device_status());
  EXPECT_EQ(driver.device_status()->units, Units::kMillimetres);  // written via installation mode
  EXPECT_EQ(driver.device_status()->software_version, "V02.10");
  EXPECT_EQ(driver.stats().crc_errors, 0u);
  EXPECT_EQ(driver.stats().connects, 1u);

  const sensors::LaserScan& s = scans.back().scan;
  ASSERT_EQ(s.ranges.size(), 181u);
  EXPECT_NEAR(s.angle_min, -M_PI / 2, 1e-9);
  EXPECT_NEAR(s.angle_increment, M_PI / 180, 1e-12);
  EXPECT_NEAR(s.range_max, 8.183, 1e-9);
  EXPECT_NEAR(s.range_min, 0.001, 1e-12);
  EXPECT_NEAR(s.scan_time, 1.0 / 75, 1e-9);
  expect_ranges_match_room(s, *rig.room, 0.001);
  // Beam 90 looks straight ahead through the doorway; beam 0 hits the right wall at 2.5 m.
  EXPECT_FLOAT_EQ(s.ranges[90], static_cast<float>(s.range_max));
  EXPECT_NEAR(s.ranges[0], 2.5, 0.0006);
}

TEST(Lms2xxDriver, TimestampsTrackTheEmulatedAcquisitionTime)
{
  Rig rig;
  Lms2xxDriver driver(fast_options(rig.emulator.port_path()));
  std::vector<Lms2xxScan> scans;
  ASSERT_TRUE(run_until(driver, &scans, [&] { return scans.size() >= 40; })) << driver.status_text();
  const auto truth = rig.emulator.sent_scans();
  ASSERT_GE(truth.size(), scans.size());
  // The device streams only since the driver asked, and nothing was lost (no CRC errors),
  // so scan i is the emulator's record i.
  ASSERT_EQ(driver.stats().crc_errors, 0u);
  for (size_t i = 1; i < scans.size(); ++i) {
    EXPECT_GT(scans[i].scan.utime, scans[i - 1].scan.utime);
    const int64_t err = scans[i].scan.utime - truth[i].first_beam_utime;
    // The estimate is late only by scheduling delays; it is never early by more than rounding.
    // Generous upper bound: this guards against a wrong formula (off by a scan period or the
    // wire time), not against a loaded machine.
    EXPECT_GE(err, -100) << "scan " << i;
    EXPECT_LT(err, 150'000) << "scan " << i;
  }
}

TEST(Lms2xxDriver, HalfDegreeVariantGives361BeamsInCentimetres)
{
  Rig rig;
  auto o = fast_options(rig.emulator.port_path());
  o.variant = {180, 50};
  o.units = Units::kCentimetres;
  Lms2xxDriver driver(o);
  std::vector<Lms2xxScan> scans;
  ASSERT_TRUE(run_until(driver, &scans, [&] { return scans.size() >= 10; })) << driver.status_text();
  const sensors::LaserScan& s = scans.back().scan;
  ASSERT_EQ(s.ranges.size(), 361u);
  EXPECT_NEAR(s.angle_increment, M_PI / 360, 1e-12);
  EXPECT_NEAR(s.range_max, 81.83, 1e-9);  // 80 m mode
  EXPECT_NEAR(s.scan_time, 2.0 / 75, 1e-9);
  expect_ranges_match_room(s, *rig.room, 0.01);
}

TEST(Lms2xxDriver, GarbageIsSkippedAndTheStreamContinues)
{
  Rig rig;
  Lms2xxDriver driver(fast_options(rig.emulator.port_path()));
  std::vector<Lms2xxScan> scans;
  ASSERT_TRUE(run_until(driver, &scans, [&] { return scans.size() >= 5; })) << driver.status_text();
  // Noise with a fake start (STX, host address, absurd length) and a NAK-looking byte.
  rig.emulator.inject_garbage({0x11, 0x22, 0x02, 0x80, 0xF0, 0xFF, 0x33, 0x02, 0x99, 0x44});
  const size_t before = scans.size();
  ASSERT_TRUE(run_until(driver, &scans, [&] { return scans.size() >= before + 10; })) << driver.status_text();
  EXPECT_GE(driver.stats().resyncs, 1u);
  EXPECT_GE(driver.stats().skipped_bytes, 8u);
  EXPECT_EQ(driver.stats().crc_errors, 0u);
  EXPECT_EQ(driver.stats().connects, 1u);  // never lost the link
  expect_ranges_match_room(scans.back().scan, *rig.room, 0.001);
}

TEST(Lms2xxDriver, OneCorruptCrcDropsExactlyThatScan)
{
  Rig rig;
  Lms2xxDriver driver(fast_options(rig.emulator.port_path()));
  std::vector<Lms2xxScan> scans;
  ASSERT_TRUE(run_until(driver, &scans, [&] { return scans.size() >= 5; })) << driver.status_text();
  rig.emulator.corrupt_next_scans(1);
  const size_t before = scans.size();
  ASSERT_TRUE(run_until(driver, &scans, [&] { return scans.size() >= before + 10; })) << driver.status_text();
  // Stop the stream, drain, and account for every telegram the device sent.
  rig.emulator.set_silent(true);
  const auto sent_total = [&] { return rig.emulator.stats().scans_sent; };
  const uint64_t sent = sent_total();
  run_until(driver, &scans, [&] { return false; }, 100ms);
  EXPECT_EQ(driver.stats().crc_errors, 1u);
  EXPECT_EQ(scans.size(), sent - 1);
  const auto truth = rig.emulator.sent_scans();
  int corrupted = 0;
  for (const auto& t : truth) corrupted += t.corrupted;
  EXPECT_EQ(corrupted, 1);
}

TEST(Lms2xxDriver, ReconnectsAfterUnplugAndReplug)
{
  Rig rig;
  Lms2xxDriver driver(fast_options(rig.emulator.port_path()));
  std::vector<Lms2xxScan> scans;
  ASSERT_TRUE(run_until(driver, &scans, [&] { return scans.size() >= 5; })) << driver.status_text();
  rig.emulator.unplug();
  ASSERT_TRUE(run_until(driver, &scans, [&] { return driver.state() == Lms2xxDriver::State::kDisconnected; }))
      << driver.status_text();
  // The port is gone: opening fails until it is back.
  run_until(driver, &scans, [&] { return false; }, 300ms);
  EXPECT_EQ(driver.state(), Lms2xxDriver::State::kDisconnected);
  EXPECT_GT(driver.stats().open_failures, 0u);
  const size_t before = scans.size();
  // Replugged adapter: the LMS kept running at 500000 baud and is still streaming, so the
  // driver must find it at its session rate, not its power-on rate.
  rig.emulator.replug();
  ASSERT_TRUE(run_until(driver, &scans, [&] { return scans.size() >= before + 10; })) << driver.status_text();
  EXPECT_EQ(driver.stats().connects, 2u);
  EXPECT_GE(driver.stats().disconnects, 1u);
  expect_ranges_match_room(scans.back().scan, *rig.room, 0.001);
}

TEST(Lms2xxDriver, ReconnectsAfterPowerCycle)
{
  Rig rig;
  Lms2xxDriver driver(fast_options(rig.emulator.port_path()));
  std::vector<Lms2xxScan> scans;
  ASSERT_TRUE(run_until(driver, &scans, [&] { return scans.size() >= 5; })) << driver.status_text();
  rig.emulator.unplug();
  rig.emulator.replug(/*power_cycle=*/true);  // back at 9600 baud, not streaming
  const size_t before = scans.size();
  ASSERT_TRUE(run_until(driver, &scans, [&] { return scans.size() >= before + 5; })) << driver.status_text();
  EXPECT_EQ(driver.stats().connects, 2u);
  EXPECT_EQ(rig.emulator.baud(), 500000);
}

TEST(Lms2xxDriver, SilentDeviceTriggersReconnect)
{
  Rig rig;
  Lms2xxDriver driver(fast_options(rig.emulator.port_path()));
  std::vector<Lms2xxScan> scans;
  ASSERT_TRUE(run_until(driver, &scans, [&] { return scans.size() >= 5; })) << driver.status_text();
  rig.emulator.set_silent(true);
  ASSERT_TRUE(run_until(driver, &scans, [&] { return driver.stats().disconnects >= 1; })) << driver.status_text();
  EXPECT_NE(driver.last_error().find("silent"), std::string::npos) << driver.last_error();
  rig.emulator.set_silent(false);
  const size_t before = scans.size();
  ASSERT_TRUE(run_until(driver, &scans, [&] { return scans.size() >= before + 5; })) << driver.status_text();
  EXPECT_EQ(driver.stats().connects, 2u);
}

TEST(Lms2xxDriver, LowerSessionBaudStreamsAtTheRateTheLineAllows)
{
  Rig rig;
  auto o = fast_options(rig.emulator.port_path());
  o.desired_baud = 38400;
  o.silence_timeout = 1000ms;
  Lms2xxDriver driver(o);
  std::vector<Lms2xxScan> scans;
  ASSERT_TRUE(run_until(driver, &scans, [&] { return scans.size() >= 6; })) << driver.status_text();
  EXPECT_EQ(rig.emulator.baud(), 38400);
  EXPECT_EQ(driver.current_baud(), 38400);
  // A 372-byte telegram takes 97 ms at 38400 baud: the device skips the scans in between.
  EXPECT_GT(rig.emulator.stats().scans_skipped, 5 * rig.emulator.stats().scans_sent / 2);
  // Consecutive scans are a whole number of rotations (8 at this rate) apart.
  const double dt = (scans.back().scan.utime - scans[scans.size() - 2].scan.utime) * 1e-6;
  EXPECT_GT(dt, 7.5 / 75);
}

TEST(Lms2xxDriver, WrongPasswordIsReportedAndRetried)
{
  Rig rig;  // cm; the driver wants mm, so it must write the configuration
  auto o = fast_options(rig.emulator.port_path());
  o.password = "WRONG_PW";
  Lms2xxDriver driver(o);
  std::vector<Lms2xxScan> scans;
  ASSERT_TRUE(run_until(driver, &scans, [&] { return driver.stats().disconnects >= 2; })) << driver.status_text();
  EXPECT_NE(driver.last_error().find("password"), std::string::npos) << driver.last_error();
  EXPECT_TRUE(scans.empty());
}

TEST(Lms2xxEmulator, HostAtTheWrongBaudGetsNoAnswer)
{
  Rig rig;  // device at 9600
  SerialPort port(rig.emulator.port_path(), 19200);
  const auto req = frame(request_status());
  ASSERT_TRUE(port.write_all(req.data(), req.size()));
  TelegramParser parser(kAddressHost);
  uint8_t buf[512];
  const auto end = std::chrono::steady_clock::now() + 300ms;
  size_t telegrams = 0;
  while (std::chrono::steady_clock::now() < end) {
    if (!port.wait_readable(20ms)) continue;
    const auto r = port.read_some(buf, sizeof buf);
    if (r.status == SerialPort::ReadStatus::kData) telegrams += parser.feed(buf, r.size).telegrams.size();
  }
  EXPECT_EQ(telegrams, 0u);
  EXPECT_GT(rig.emulator.stats().garbled_rx_bytes, 0u);
  // At the right rate the same request is answered.
  port.set_baud(9600);
  ASSERT_TRUE(port.write_all(req.data(), req.size()));
  const auto end2 = std::chrono::steady_clock::now() + 3s;
  while (telegrams == 0 && std::chrono::steady_clock::now() < end2) {
    if (!port.wait_readable(20ms)) continue;
    const auto r = port.read_some(buf, sizeof buf);
    if (r.status == SerialPort::ReadStatus::kData) telegrams += parser.feed(buf, r.size).telegrams.size();
  }
  EXPECT_EQ(telegrams, 1u);
}

TEST(Lms2xxEmulator, ResetAcknowledgesThenSendsPowerOnAtTheInitialBaud)
{
  EmulatorOptions eo;
  eo.reset_duration = 500ms;  // the host must switch back to 9600 before the power-on telegram
  Rig rig(eo);
  SerialPort port(rig.emulator.port_path(), 9600);
  TelegramParser parser(kAddressHost);
  std::vector<Telegram> got;
  int acks = 0;
  uint8_t buf[256];
  auto read_for = [&](std::chrono::milliseconds d, size_t want) {
    const auto end = std::chrono::steady_clock::now() + d;
    while (got.size() < want && std::chrono::steady_clock::now() < end) {
      if (!port.wait_readable(20ms)) continue;
      const auto r = port.read_some(buf, sizeof buf);
      if (r.status != SerialPort::ReadStatus::kData) continue;
      auto out = parser.feed(buf, r.size);
      acks += out.acks;
      for (auto& t : out.telegrams) got.push_back(t.telegram);
    }
  };
  // Move the device to 38400 first, so the reset visibly returns it to its power-on rate.
  auto req = frame(request_baud(Baud::k38400));
  ASSERT_TRUE(port.write_all(req.data(), req.size()));
  read_for(3s, 1);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(decode_mode_reply(*as_reply(got[0])), 0x00);
  port.set_baud(38400);
  std::this_thread::sleep_for(50ms);  // the device switches once its reply is out
  ASSERT_EQ(rig.emulator.baud(), 38400);
  req = frame(request_reset());
  ASSERT_TRUE(port.write_all(req.data(), req.size()));
  read_for(3s, 2);
  ASSERT_EQ(got.size(), 2u);
  EXPECT_EQ(got[1].command(), reply::kResetAck);
  port.set_baud(9600);  // after the reset the LMS talks at its power-on rate again
  read_for(3s, 3);
  ASSERT_EQ(got.size(), 3u);
  EXPECT_EQ(got[2].command(), reply::kPowerOn);
  const auto text = as_reply(got[2])->data;
  EXPECT_EQ(std::string(text.begin(), text.end()), "LMS291;S05");
  EXPECT_EQ(acks, 2);
  EXPECT_EQ(rig.emulator.baud(), 9600);
}

TEST(Lms2xxEmulator, BrokenRequestIsAnsweredWithNak)
{
  Rig rig;
  SerialPort port(rig.emulator.port_path(), 9600);
  auto req = frame(request_status());
  req.back() ^= 0x01;
  ASSERT_TRUE(port.write_all(req.data(), req.size()));
  TelegramParser parser(kAddressHost);
  uint8_t buf[64];
  int naks = 0;
  const auto end = std::chrono::steady_clock::now() + 3s;
  while (naks == 0 && std::chrono::steady_clock::now() < end) {
    if (!port.wait_readable(20ms)) continue;
    const auto r = port.read_some(buf, sizeof buf);
    if (r.status == SerialPort::ReadStatus::kData) naks += parser.feed(buf, r.size).naks;
  }
  EXPECT_EQ(naks, 1);
  EXPECT_EQ(rig.emulator.stats().naks_sent, 1u);
}

}  // namespace
}  // namespace rgnav::drivers::sick
