// Tests of the test-support library itself: sample messages are valid for every type, the
// generated reflection agrees with the generated validators, child processes behave.
#include <gtest/gtest.h>
#include <signal.h>

#include <set>

#include "bus/typed.h"
#include "child_process.h"
#include "message_records.h"
#include "rgnav_test_reflection.hpp"
#include "runtime/signal_watcher.h"
#include "sample_messages.h"

namespace rgnav::testing {
namespace {

template <class T>
void check_samples(const char* name)
{
  std::set<std::string> distinct;
  for (uint32_t v = 0; v < 12; ++v) {
    const T msg = sample<T>(v);
    std::vector<uint8_t> buf;
    std::string why;
    ASSERT_TRUE(bus::encode(msg, &buf, &why)) << name << " variant " << v << ": " << why;
    T back;
    ASSERT_TRUE(bus::decode(buf.data(), buf.size(), &back, &why)) << name << " variant " << v << ": " << why;
    EXPECT_EQ(to_json(back), to_json(msg)) << name;
    // The layout walk must consume exactly the encoding and find its slots in bounds.
    const auto slots = wire_layout<T>(buf.data(), buf.size());
    for (const auto& s : slots) EXPECT_LE(s.offset + static_cast<size_t>(s.size), buf.size()) << name << s.field;
    distinct.insert(to_json(msg));
    EXPECT_EQ(to_json(sample<T>(v)), to_json(msg)) << name << ": samples must be deterministic";
  }
  EXPECT_GE(distinct.size(), 6u) << name << ": variants should differ";
}

TEST(SampleMessages, EveryTypeEncodesDecodesAndVaries)
{
#define CHECK_TYPE(T) check_samples<T>(#T);
  RGNAV_FOR_EACH_TYPE(CHECK_TYPE)
#undef CHECK_TYPE
}

TEST(SampleMessages, LaserAndImagesHaveRequestedShape)
{
  const auto scan = sample_laser_scan(7, 361);
  EXPECT_EQ(scan.nranges, 361);
  EXPECT_EQ(scan.scan_id, 7);
  const auto stereo = sample_stereo(3, 720, 720, image_t::FORMAT_GRAY8);
  EXPECT_EQ(stereo.left.size, 720 * 720);
  std::vector<uint8_t> buf;
  std::string why;
  EXPECT_TRUE(bus::encode(stereo, &buf, &why)) << why;
  EXPECT_GT(buf.size(), 1'000'000u);
}

TEST(WireLayout, FindsCountsStringsFloatsAndEnums)
{
  const auto scan = sample_laser_scan(1, 181, /*variant with intensities*/ 1);
  std::vector<uint8_t> buf;
  std::string why;
  ASSERT_TRUE(bus::encode(scan, &buf, &why));
  const auto slots = wire_layout<laser_scan_t>(buf.data(), buf.size());
  int counts = 0, strings = 0, floats = 0;
  for (const auto& s : slots) {
    counts += s.kind == SlotKind::kCount;
    strings += s.kind == SlotKind::kStringLength;
    floats += s.kind == SlotKind::kFloat;
  }
  EXPECT_EQ(counts, 2);             // nranges, nintensities
  EXPECT_EQ(strings, 1);            // sensor
  EXPECT_EQ(floats, 5 + 181 + 181);  // header floats, ranges, intensities
  // The string length sits right after fingerprint, utime, scan_id.
  EXPECT_EQ(slots[0].offset, 24u);
  EXPECT_EQ(slots[0].field, ".sensor");
}

TEST(MessageRecords, HexRoundTrip)
{
  const std::vector<uint8_t> bytes = {0, 1, 0x7f, 0x80, 0xff};
  EXPECT_EQ(to_hex(bytes.data(), bytes.size()), "00017f80ff");
  EXPECT_EQ(from_hex("00017f80ff"), bytes);
  EXPECT_THROW(from_hex("0g"), std::invalid_argument);
}

TEST(ChildProcess, ReportsExitCodeAndCapturesStderr)
{
  TempDir dir;
  ChildOptions o;
  o.stderr_path = dir.file("err.txt");
  const auto s = run_to_completion({"sh", "-c", "echo complaint >&2; exit 3"}, std::chrono::seconds(10), o);
  EXPECT_TRUE(s.exited);
  EXPECT_EQ(s.code, 3);
  EXPECT_EQ(read_file(dir.file("err.txt")), "complaint\n");
}

TEST(ChildProcess, SignalsReachChildEvenWhenParentBlocksThem)
{
  // The runtime blocks SIGINT/SIGTERM in its threads; children must not inherit that.
  runtime::SignalWatcher blocked_here;
  ChildProcess child({"sleep", "30"});
  EXPECT_FALSE(child.wait_for(std::chrono::milliseconds(50)).has_value());
  ASSERT_TRUE(child.signal(SIGTERM));
  const auto s = child.wait_for(std::chrono::seconds(10));
  ASSERT_TRUE(s.has_value());
  EXPECT_TRUE(s->signaled);
  EXPECT_EQ(s->signal, SIGTERM);
}

TEST(ChildProcess, DestructorKillsTheWholeGroup)
{
  TempDir dir;
  pid_t grandchild = 0;
  {
    ChildProcess child({"sh", "-c", "sleep 30 & echo $! > " + dir.file("pid") + "; wait"});
    for (int i = 0; i < 500 && read_file(dir.file("pid")).empty(); ++i) usleep(10'000);
    grandchild = std::stoi(read_file(dir.file("pid")));
  }
  // The grandchild was re-parented to init (or us as subreaper) and killed; give it a moment.
  bool gone = false;
  for (int i = 0; i < 500 && !gone; ++i) {
    gone = kill(grandchild, 0) != 0;
    if (!gone) {
      // A zombie still answers kill(0); it is dead if its state is Z.
      const std::string stat = read_file("/proc/" + std::to_string(grandchild) + "/stat");
      gone = stat.empty() || stat.find(") Z") != std::string::npos;
    }
    if (!gone) usleep(10'000);
  }
  EXPECT_TRUE(gone);
}

TEST(ProcessGroup, StopAllEndsEveryChild)
{
  std::vector<pid_t> pids;
  {
    ProcessGroup group;
    pids.push_back(group.start({"sleep", "30"}).pid());
    pids.push_back(group.start({"sh", "-c", "trap '' TERM; sleep 30"}).pid());  // ignores SIGTERM
    EXPECT_EQ(group.size(), 2u);
    group.stop_all(std::chrono::milliseconds(300));
    EXPECT_EQ(group.size(), 0u);
  }
  for (pid_t p : pids) EXPECT_NE(kill(p, 0), 0) << "child " << p << " still exists";
}

TEST(ChildProcess, MissingExecutableThrows)
{
  EXPECT_THROW(ChildProcess({"/nonexistent/rgnav_no_such_program"}), std::runtime_error);
}

}  // namespace
}  // namespace rgnav::testing
