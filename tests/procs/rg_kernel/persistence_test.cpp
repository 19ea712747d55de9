// The RG kernel's promise: a SIGKILL at any instant followed by a restart yields the map of
// every input acknowledged before the kill. A kill can only leave the journal cut at some
// byte; these tests cut it at many bytes and compare the restarted map with the reference.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "bus/fake_bus.h"
#include "persist/atomic_file.h"
#include "persist/journal.h"
#include "procs/rg_kernel/rg_kernel_node.h"
#include "rgmap/rgmap_json.h"
#include "synthetic_world.h"

namespace rgnav::rg_kernel {
namespace {

namespace fs = std::filesystem;
using Eigen::Vector2d;

std::string fresh_dir(const std::string& name)
{
  const auto d = fs::path(::testing::TempDir()) / ("rgk_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d.string();
}

struct KernelProcess
{
  explicit KernelProcess(const std::string& dir)
  {
    auto b = std::make_unique<bus::FakeBus>();
    bus = b.get();
    runtime::NodeOptions o;
    o.name = "rg_kernel";
    node = std::make_unique<runtime::Node>(o, std::move(b));
    NodeConfig c;
    c.state_dir = dir;
    c.fsync_each_input = false;  // the test cuts the file itself; fsync only slows it down
    kernel = std::make_unique<RgKernelNode>(*node, c);
  }
  std::string map_json() { return rgmap::to_json(const_cast<RgKernel&>(kernel->kernel()).refreshed_map()).dump(); }
  bus::FakeBus* bus;
  std::unique_ptr<runtime::Node> node;
  std::unique_ptr<RgKernelNode> kernel;
};

std::vector<std::pair<std::string, std::vector<uint8_t>>> inputs()
{
  std::vector<std::pair<std::string, std::vector<uint8_t>>> out;
  const auto walls = testing::two_rooms();
  int64_t t = 1'000'000, id = 1;
  auto scan = [&](double x, double th) {
    aligned_scan_t m{};
    m.utime = (t += 200'000);
    m.scan_id = id++;
    m.map_from_base.x = x;
    m.map_from_base.y = 1.5;
    m.map_from_base.theta = th;
    m.odom_from_base = m.map_from_base;
    laser_scan_t& s = m.scan;
    s.utime = m.utime;
    s.scan_id = m.scan_id;
    s.sensor = "laser_front";
    s.angle_min = static_cast<float>(-M_PI / 2);
    s.angle_increment = static_cast<float>(M_PI / 180);
    s.range_max = 8.0f;
    s.nranges = 181;
    s.ranges.assign(181, 8.0f);
    const auto pts = testing::cast(walls, geometry::Pose2(x, 1.5, th));
    // cast() drops max-range beams; recover each beam's range from its bearing.
    for (const auto& p : pts) {
      const int beam = static_cast<int>(std::lround((std::atan2(p.y(), p.x()) + M_PI / 2) / (M_PI / 180)));
      if (beam >= 0 && beam < 181) s.ranges[static_cast<size_t>(beam)] = static_cast<float>(p.norm());
    }
    std::vector<uint8_t> buf;
    std::string why;
    EXPECT_TRUE(bus::encode(m, &buf, &why)) << why;
    out.push_back({"ALIGNED_SCAN", buf});
  };
  for (double x = 1.0; x < 3.9; x += 0.3) scan(x, 0);
  gateway_event_t e{};
  e.utime = (t += 1000);
  e.scan_id = id - 1;
  e.event = gateway_event_t::EVENT_TRAVERSED;
  e.track_id = 7;
  e.gateway_class = gateway_event_t::CLASS_DOOR;
  e.map_from_base.x = 4.3;
  e.map_from_base.y = 1.5;
  e.npoints = 2;
  e.gateway_points.resize(2);
  e.gateway_points[0].x = 4;
  e.gateway_points[0].y = 1;
  e.gateway_points[1].x = 4;
  e.gateway_points[1].y = 2;
  std::vector<uint8_t> buf;
  std::string why;
  EXPECT_TRUE(bus::encode(e, &buf, &why)) << why;
  out.push_back({"GATEWAY_EVENTS", buf});
  for (double x = 4.5; x < 7.5; x += 0.3) scan(x, 0);
  return out;
}

TEST(RgKernelPersistence, KillAtAnyByteRestartsToTheAcknowledgedMap)
{
  const auto in = inputs();
  const std::string dir = fresh_dir("ref");
  std::vector<std::string> map_after;     // reference map after k inputs
  std::vector<uintmax_t> journal_size;    // journal bytes after k inputs
  {
    KernelProcess ref(dir);
    map_after.push_back(ref.map_json());
    journal_size.push_back(0);
    for (const auto& [ch, bytes] : in) {
      ref.bus->publish(ch, bytes.data(), bytes.size());
      map_after.push_back(ref.map_json());
      journal_size.push_back(fs::file_size(dir + "/inputs.journal"));
    }
  }
  std::ifstream jin(dir + "/inputs.journal", std::ios::binary);
  const std::string journal((std::istreambuf_iterator<char>(jin)), std::istreambuf_iterator<char>());
  ASSERT_EQ(journal.size(), journal_size.back());

  // Cut points: every record boundary, and a few bytes into the next record.
  std::vector<size_t> cuts;
  for (size_t k = 0; k < journal_size.size(); ++k) {
    cuts.push_back(journal_size[k]);
    if (k + 1 < journal_size.size()) cuts.push_back(journal_size[k] + 7);
  }
  for (const size_t cut : cuts) {
    const std::string d = fresh_dir("cut");
    std::ofstream(d + "/inputs.journal", std::ios::binary) << journal.substr(0, cut);
    KernelProcess restarted(d);
    size_t complete = 0;
    while (complete + 1 < journal_size.size() && journal_size[complete + 1] <= cut) ++complete;
    EXPECT_EQ(restarted.map_json(), map_after[complete]) << "journal cut at byte " << cut;
    EXPECT_EQ(restarted.kernel->restored_inputs(), static_cast<int64_t>(complete));
  }
}

TEST(RgKernelPersistence, RestartContinuesAsIfUninterrupted)
{
  const auto in = inputs();
  const std::string whole = fresh_dir("whole"), split = fresh_dir("split");
  std::string expected;
  {
    KernelProcess p(whole);
    for (const auto& [ch, b] : in) p.bus->publish(ch, b.data(), b.size());
    expected = p.map_json();
  }
  {
    KernelProcess first(split);
    for (size_t k = 0; k < in.size() / 2; ++k) first.bus->publish(in[k].first, in[k].second.data(), in[k].second.size());
  }
  KernelProcess second(split);
  for (size_t k = in.size() / 2; k < in.size(); ++k) second.bus->publish(in[k].first, in[k].second.data(), in[k].second.size());
  EXPECT_EQ(second.map_json(), expected);
  // And it published what it restored, with a checkpoint on disk that loads.
  EXPECT_FALSE(second.bus->published_on("RG_MAP").empty());
  second.kernel->publish();
}

TEST(AtomicFile, DetectsTruncationAndCorruption)
{
  const std::string d = fresh_dir("atomic");
  const std::string path = d + "/x.json";
  EXPECT_FALSE(persist::read_checked(path));
  persist::write_atomically(path, "{\"a\": 1}");
  EXPECT_EQ(*persist::read_checked(path), "{\"a\": 1}");
  std::string raw;
  {
    std::ifstream in(path, std::ios::binary);
    raw.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  std::ofstream(path, std::ios::binary | std::ios::trunc) << raw.substr(0, raw.size() - 2);
  EXPECT_THROW(persist::read_checked(path), persist::CorruptFile);
  std::string flipped = raw;
  flipped.back() = 'X';
  std::ofstream(path, std::ios::binary | std::ios::trunc) << flipped;
  EXPECT_THROW(persist::read_checked(path), persist::CorruptFile);
  std::ofstream(path, std::ios::binary | std::ios::trunc) << "garbage";
  EXPECT_THROW(persist::read_checked(path), persist::CorruptFile);
}

TEST(Journal, CorruptRecordCutsTheTailAndIsReported)
{
  const std::string d = fresh_dir("journal");
  {
    persist::Journal j(d + "/j", false);
    j.append(1, "first");
    j.append(2, "second");
    j.append(1, "third");
  }
  {
    std::fstream f(d + "/j", std::ios::binary | std::ios::in | std::ios::out);
    f.seekp(16 + 5 + 16 + 2);  // inside the payload of "second"
    f.put('#');
  }
  {
    persist::Journal j(d + "/j", false);
    ASSERT_EQ(j.recovered().size(), 1u);
    EXPECT_EQ(j.recovered()[0].bytes, "first");
    EXPECT_NE(j.damage().find("CRC"), std::string::npos);
    j.append(3, "fourth");
  }
  persist::Journal again(d + "/j", false);
  ASSERT_EQ(again.recovered().size(), 2u);
  EXPECT_EQ(again.recovered()[1].bytes, "fourth");
  EXPECT_TRUE(again.damage().empty());
}

TEST(Journal, OneWriterAtATime)
{
  const std::string d = fresh_dir("lock");
  persist::Journal first(d + "/j", false);
  first.append(1, "a");
  const auto start = std::chrono::steady_clock::now();
  EXPECT_THROW(persist::Journal(d + "/j", false), std::runtime_error);
  EXPECT_GE(std::chrono::steady_clock::now() - start, std::chrono::seconds(2));  // it waited for the owner
}

}  // namespace
}  // namespace rgnav::rg_kernel
