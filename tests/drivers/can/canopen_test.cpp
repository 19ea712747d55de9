// CANopen master pieces against the drive emulator on a simulated bus: SDO round trips,
// aborts, timeouts and retries; NMT; heartbeat production and consumption.
#include <gtest/gtest.h>

#include <optional>

#include "bus/can_frames.h"
#include "canopen/cia402.h"
#include "canopen/emcy.h"
#include "canopen/protocol.h"
#include "canopen/sdo.h"
#include "emulator/drive_emulator.h"
#include "master/heartbeat_monitor.h"
#include "master/sdo_client.h"
#include "sim_can_bus.h"

namespace rgnav::can {
namespace {

using namespace std::chrono_literals;
using canopen::NmtState;
using emulator::DriveEmulator;
using master::SdoClient;
using master::SdoResult;
namespace sdo = canopen::sdo;

TEST(SdoMessages, EncodeParseRoundTrip)
{
  const can_frame d = sdo::download_request(5, 0x6083, 0, 0x12345678, 4);
  EXPECT_EQ(d.can_id, 0x605u);
  EXPECT_EQ(d.data[0], 0x23);  // expedited, size indicated, 4 bytes
  auto m = sdo::parse(d);
  EXPECT_EQ(m.type, sdo::Message::Type::kDownloadRequest);
  EXPECT_EQ(m.index, 0x6083);
  EXPECT_EQ(m.value, 0x12345678u);
  EXPECT_EQ(m.size, 4);
  const can_frame d1 = sdo::download_request(5, 0x6060, 0, 3, 1);
  EXPECT_EQ(d1.data[0], 0x2F);
  const can_frame u = sdo::upload_response(5, 0x6041, 0, 0x0237, 2);
  EXPECT_EQ(u.can_id, 0x585u);
  EXPECT_EQ(u.data[0], 0x4B);
  m = sdo::parse(u);
  EXPECT_EQ(m.type, sdo::Message::Type::kUploadResponse);
  EXPECT_EQ(m.value, 0x0237u);
  const can_frame a = sdo::abort(0x585, 0x1234, 1, sdo::kNoObject);
  m = sdo::parse(a);
  EXPECT_EQ(m.type, sdo::Message::Type::kAbort);
  EXPECT_EQ(m.abort_code, sdo::kNoObject);
  EXPECT_NE(sdo::abort_text(sdo::kNoObject).find("does not exist"), std::string::npos);
}

// A master-side SDO client and one emulated drive on a simulated bus.
class SdoFixture : public ::testing::Test
{
 protected:
  SdoFixture()
  {
    const int m = bus.add([this](const can_frame& f, auto now) { client.handle(f, now); });
    const int d = bus.add([this](const can_frame& f, auto now) { drive.handle(f, now); });
    master_sink = bus.sink(m);
    drive_sink = bus.sink(d);
    drive.power_on(bus.now());
    bus.deliver();
  }
  void run(std::chrono::milliseconds duration)
  {
    for (auto t = 0ms; t < duration; t += 1ms) {
      bus.advance(1ms);
      client.tick(bus.now());
      drive.tick(bus.now());
      bus.deliver();
    }
  }
  SdoResult transfer(std::function<void(SdoClient::Callback)> start)
  {
    std::optional<SdoResult> r;
    start([&r](const SdoResult& res) { r = res; });
    for (int i = 0; i < 2000 && !r; ++i) run(1ms);
    EXPECT_TRUE(r) << "transfer never finished";
    return r.value_or(SdoResult{});
  }

  testing::SimCanBus bus;
  std::function<void(const can_frame&)> master_sink, drive_sink;
  master::SdoClientOptions options{std::chrono::milliseconds(20), 2};
  SdoClient client{options, [this](const can_frame& f) { master_sink(f); }};
  DriveEmulator drive{[] {
                        emulator::DriveEmulatorOptions o;
                        o.node_id = 4;
                        return o;
                      }(),
                      [this](const can_frame& f) { drive_sink(f); }};
};

TEST_F(SdoFixture, UploadAndDownloadRoundTrips)
{
  auto r = transfer([&](auto cb) { client.upload(4, 0x1000, 0, cb); });
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.value & 0xFFFF, 402u);
  EXPECT_EQ(r.size, 4);
  r = transfer([&](auto cb) { client.upload(4, 0x1018, 1, cb); });
  ASSERT_TRUE(r.ok);
  EXPECT_EQ(r.value, 0x555u);  // vendor id from the EDS
  r = transfer([&](auto cb) { client.download(4, 0x6083, 0, 123456, 4, cb); });
  ASSERT_TRUE(r.ok) << r.error;
  r = transfer([&](auto cb) { client.upload(4, 0x6083, 0, cb); });
  EXPECT_EQ(r.value, 123456u);
  // Signed 8-bit object: modes of operation and its display.
  r = transfer([&](auto cb) { client.download(4, 0x6060, 0, 3, 1, cb); });
  ASSERT_TRUE(r.ok) << r.error;
  r = transfer([&](auto cb) { client.upload(4, 0x6061, 0, cb); });
  EXPECT_EQ(r.value, 3u);
  EXPECT_EQ(r.size, 1);
}

TEST_F(SdoFixture, AbortsCarryTheServersReason)
{
  auto r = transfer([&](auto cb) { client.upload(4, 0x2000, 0, cb); });
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.abort_code, sdo::kNoObject);
  EXPECT_NE(r.error.find("0x2000"), std::string::npos) << r.error;
  r = transfer([&](auto cb) { client.upload(4, 0x1018, 9, cb); });
  EXPECT_EQ(r.abort_code, sdo::kNoSubIndex);
  r = transfer([&](auto cb) { client.download(4, 0x6041, 0, 1, 2, cb); });
  EXPECT_EQ(r.abort_code, sdo::kReadOnly);
  r = transfer([&](auto cb) { client.download(4, 0x6083, 0, 1, 2, cb); });
  EXPECT_EQ(r.abort_code, sdo::kLengthTooLow);
  r = transfer([&](auto cb) { client.download(4, 0x6060, 0, 7, 1, cb); });  // mode 7 (ip) unsupported
  EXPECT_EQ(r.abort_code, sdo::kInvalidValue);
  // PDO mapping rules: only while the PDO is invalid; only mappable objects; <= 64 bits.
  r = transfer([&](auto cb) { client.download(4, 0x1600, 1, 0x60FF0020, 4, cb); });
  EXPECT_EQ(r.abort_code, sdo::kDeviceState);
  ASSERT_TRUE(transfer([&](auto cb) { client.download(4, 0x1400, 1, 0x80000204, 4, cb); }).ok);
  ASSERT_TRUE(transfer([&](auto cb) { client.download(4, 0x1600, 0, 0, 1, cb); }).ok);
  r = transfer([&](auto cb) { client.download(4, 0x1600, 1, 0x60410010, 4, cb); });  // statusword is ro
  EXPECT_EQ(r.abort_code, sdo::kNotMappable);
  r = transfer([&](auto cb) { client.download(4, 0x1600, 1, 0x60830020, 4, cb); });  // not mappable
  EXPECT_EQ(r.abort_code, sdo::kNotMappable);
  r = transfer([&](auto cb) { client.download(4, 0x1600, 1, 0x60FF0010, 4, cb); });  // wrong length
  EXPECT_EQ(r.abort_code, sdo::kLengthMismatch);
  for (uint8_t s = 1; s <= 3; ++s)
    ASSERT_TRUE(transfer([&](auto cb) { client.download(4, 0x1600, s, 0x60FF0020, 4, cb); }).ok);
  r = transfer([&](auto cb) { client.download(4, 0x1600, 0, 3, 1, cb); });  // 96 bits
  EXPECT_EQ(r.abort_code, sdo::kPdoTooLong);
}

TEST_F(SdoFixture, TimeoutRetriesThenAborts)
{
  bus.set_connected(1, false);  // the drive hears nothing
  bus.clear_log();
  auto r = transfer([&](auto cb) { client.upload(4, 0x1000, 0, cb); });
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(r.timed_out);
  EXPECT_EQ(r.abort_code, sdo::kTimeout);
  int requests = 0, aborts = 0;
  for (const auto& [from, f] : bus.log()) {
    if (frame_id(f) != 0x604) continue;
    (f.data[0] == 0x80 ? aborts : requests)++;
  }
  EXPECT_EQ(requests, 3) << "1 attempt + 2 retries";
  EXPECT_EQ(aborts, 1) << "the client aborts the transfer after the last timeout";
}

TEST_F(SdoFixture, LostRequestIsRecoveredByRetry)
{
  int dropped = 0;
  bus.set_drop([&dropped](int, const can_frame& f) { return frame_id(f) == 0x604 && dropped++ == 0; });
  auto r = transfer([&](auto cb) { client.upload(4, 0x1000, 0, cb); });
  EXPECT_TRUE(r.ok) << r.error;
  EXPECT_EQ(dropped, 2);
}

TEST_F(SdoFixture, QueuedRequestsRunInOrder)
{
  std::vector<uint32_t> got;
  for (uint16_t idx : {0x6083, 0x6084, 0x6085})
    client.download(4, idx, 0, idx, 4, [](const SdoResult&) {});
  for (uint16_t idx : {0x6083, 0x6084, 0x6085})
    client.upload(4, idx, 0, [&got](const SdoResult& r) { got.push_back(r.value); });
  run(100ms);
  EXPECT_EQ(got, (std::vector<uint32_t>{0x6083, 0x6084, 0x6085}));
  EXPECT_TRUE(client.idle(4));
}

TEST_F(SdoFixture, NmtStatesAndHeartbeatProducer)
{
  // Boot-up message on power on.
  bus.clear_log();
  drive.power_on(bus.now());
  bus.deliver();
  ASSERT_FALSE(bus.log().empty());
  EXPECT_EQ(to_string(bus.log().back().second), "704#00");
  EXPECT_EQ(drive.nmt_state(), NmtState::kPreOperational);
  // Heartbeat every 0x1017 ms once configured.
  ASSERT_TRUE(transfer([&](auto cb) { client.download(4, 0x1017, 0, 25, 2, cb); }).ok);
  bus.clear_log();
  run(1000ms);
  int beats = 0;
  for (const auto& [from, f] : bus.log())
    if (frame_id(f) == 0x704) {
      ++beats;
      EXPECT_EQ(f.data[0], 0x7F);
    }
  EXPECT_NEAR(beats, 40, 1);
  // NMT start / stop / pre-operational; SDO is refused (silent) while stopped.
  master_sink(canopen::make_nmt(canopen::NmtCommand::kStart, 4));
  bus.deliver();
  EXPECT_EQ(drive.nmt_state(), NmtState::kOperational);
  master_sink(canopen::make_nmt(canopen::NmtCommand::kStop, 0));  // broadcast
  bus.deliver();
  EXPECT_EQ(drive.nmt_state(), NmtState::kStopped);
  auto r = transfer([&](auto cb) { client.upload(4, 0x1000, 0, cb); });
  EXPECT_TRUE(r.timed_out);
  master_sink(canopen::make_nmt(canopen::NmtCommand::kEnterPreOperational, 4));
  bus.deliver();
  EXPECT_EQ(drive.nmt_state(), NmtState::kPreOperational);
  master_sink(canopen::make_nmt(canopen::NmtCommand::kStart, 9));  // another node
  bus.deliver();
  EXPECT_EQ(drive.nmt_state(), NmtState::kPreOperational);
  // Reset communication: 0x1017 back to its default (0), boot-up sent again.
  bus.clear_log();
  master_sink(canopen::make_nmt(canopen::NmtCommand::kResetCommunication, 4));
  bus.deliver();
  EXPECT_EQ(to_string(bus.log().back().second), "704#00");
  EXPECT_EQ(drive.od().get(0x1017), 0u);
}

TEST(HeartbeatMonitor, LossAfterConsumerTimeAndReturn)
{
  master::HeartbeatMonitor mon;
  mon.watch(3, 80ms);
  const auto t0 = std::chrono::steady_clock::time_point(std::chrono::seconds(10));
  EXPECT_TRUE(mon.tick(t0 + 1s).empty()) << "never seen is not lost";
  ASSERT_TRUE(mon.handle(canopen::make_heartbeat(3, NmtState::kOperational), t0));
  EXPECT_FALSE(mon.handle(canopen::make_heartbeat(4, NmtState::kOperational), t0)) << "not watched";
  EXPECT_TRUE(mon.tick(t0 + 80ms).empty());
  EXPECT_EQ(mon.tick(t0 + 81ms), std::vector<uint8_t>{3});
  EXPECT_TRUE(mon.tick(t0 + 200ms).empty()) << "reported once";
  EXPECT_TRUE(mon.lost(3));
  mon.handle(canopen::make_heartbeat(3, NmtState::kPreOperational), t0 + 300ms);
  EXPECT_FALSE(mon.lost(3));
  EXPECT_EQ(mon.state(3), NmtState::kPreOperational);
}

TEST(Cia402, StatuswordDecodingAndControlwordCommands)
{
  using namespace canopen::cia402;
  for (auto s : {PowerState::kNotReadyToSwitchOn, PowerState::kSwitchOnDisabled, PowerState::kReadyToSwitchOn,
                 PowerState::kSwitchedOn, PowerState::kOperationEnabled, PowerState::kQuickStopActive,
                 PowerState::kFaultReactionActive, PowerState::kFault}) {
    // Extra bits (voltage enabled, remote, target reached, warning) do not change the state.
    EXPECT_EQ(decode_statusword(statusword_bits(s) | sw::kVoltageEnabled | sw::kRemote | sw::kTargetReached), s)
        << to_string(s);
  }
  EXPECT_EQ(decode_statusword(0x0237), PowerState::kOperationEnabled);  // a typical real value
  EXPECT_EQ(decode_statusword(0x0250), PowerState::kSwitchOnDisabled);
  EXPECT_EQ(decode_controlword(0x06, 0), Command::kShutdown);
  EXPECT_EQ(decode_controlword(0x07, 0), Command::kSwitchOn);
  EXPECT_EQ(decode_controlword(0x0F, 0), Command::kEnableOperation);
  EXPECT_EQ(decode_controlword(0x02, 0), Command::kQuickStop);
  EXPECT_EQ(decode_controlword(0x00, 0), Command::kDisableVoltage);
  EXPECT_EQ(decode_controlword(0x80, 0x00), Command::kFaultReset);
  EXPECT_NE(decode_controlword(0x80, 0x80), Command::kFaultReset) << "only the rising edge resets";
  EXPECT_EQ(controlword_towards_enabled(PowerState::kFault, 0x80), cw::kCmdDisableVoltage);
  EXPECT_EQ(controlword_towards_enabled(PowerState::kFault, 0x00), cw::kCmdFaultReset);
}

TEST(Emcy, FrameLayout)
{
  const can_frame f = canopen::emcy::make(3, canopen::emcy::kContinuousOverCurrent, 0x03);
  EXPECT_EQ(to_string(f), "083#1023030000000000");
  auto e = canopen::emcy::parse(f);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->node_id, 3);
  EXPECT_EQ(e->error_code, 0x2310);
  EXPECT_FALSE(canopen::emcy::parse(canopen::make_sync())) << "SYNC shares 0x080 but is no EMCY";
}

}  // namespace
}  // namespace rgnav::can
