// Persistence of the scan mapper node under faults: a SIGKILL at any instant loses no scan
// that was published, scan ids continue after a restart (also when the laser's ids restart),
// and a torn or corrupt journal or snapshot is detected, reported and dropped, never loaded.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include "bad_files.h"
#include "node_harness.h"
#include "scan_mapper/mapper_state_io.h"

namespace sm = rgnav::scan_mapper;
namespace fs = std::filesystem;
using rgnav::aligned_scan_t;
using sm::testing::drive;
using sm::testing::NodeHarness;

namespace {

struct TempDir
{
  explicit TempDir(const std::string& tag)
      : path(fs::temp_directory_path() / ("rgnav_sm_" + tag + "_" + std::to_string(::getpid())))
  {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() { fs::remove_all(path); }
  fs::path path;
};

sm::PersistenceOptions persistence(const fs::path& dir, int snapshot_every)
{
  sm::PersistenceOptions p;
  p.state_file = (dir / "state.bin").string();
  p.snapshot_every_records = snapshot_every;
  return p;
}

// Newest publication (pose, revision) of every scan id.
struct Published
{
  double x, y, theta;
  int32_t revision;
};

std::map<int64_t, Published> newest_publications(const NodeHarness& h)
{
  std::map<int64_t, Published> out;
  for (const auto& a : h.published<aligned_scan_t>("ALIGNED_SCAN")) {
    auto& p = out[a.scan_id];
    if (a.revision >= p.revision) p = {a.map_from_base.x, a.map_from_base.y, a.map_from_base.theta, a.revision};
  }
  return out;
}

void write_all(int fd, const void* data, size_t n)
{
  const auto* p = static_cast<const char*>(data);
  while (n > 0) {
    const ssize_t k = ::write(fd, p, n);
    if (k <= 0) _exit(3);
    p += k;
    n -= static_cast<size_t>(k);
  }
}

bool read_all(int fd, void* data, size_t n)
{
  auto* p = static_cast<char*>(data);
  while (n > 0) {
    const ssize_t k = ::read(fd, p, n);
    if (k <= 0) return false;
    p += k;
    n -= static_cast<size_t>(k);
  }
  return true;
}

}  // namespace

// A child process maps (with loop closures and snapshots in between), reports what it
// published and is SIGKILLed at once: no destructor, no final snapshot. The restarted node
// must hold every published scan with its newest published pose, and continue the ids.
TEST(ScanMapperPersistence, SigkillLosesNoPublishedScan)
{
  TempDir dir("kill");
  const auto p = persistence(dir.path, 7);  // snapshots and journal records both in play
  int fds[2];
  ASSERT_EQ(::pipe(fds), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ::close(fds[0]);
    {
      NodeHarness h(p);
      drive(h, 0, 230);  // out, back: loop closures republish corrected scans
      const auto pubs = newest_publications(h);
      const uint64_t n = pubs.size();
      const int64_t closures = h.adapter->optimizations_applied();
      write_all(fds[1], &n, sizeof n);
      write_all(fds[1], &closures, sizeof closures);
      for (const auto& [id, pub] : pubs) {
        write_all(fds[1], &id, sizeof id);
        write_all(fds[1], &pub, sizeof pub);
      }
      ::raise(SIGKILL);  // the harness and node are never destroyed
    }
    _exit(2);
  }
  ::close(fds[1]);
  uint64_t n = 0;
  int64_t closures = 0;
  std::map<int64_t, Published> before;
  ASSERT_TRUE(read_all(fds[0], &n, sizeof n));
  ASSERT_TRUE(read_all(fds[0], &closures, sizeof closures));
  for (uint64_t i = 0; i < n; ++i) {
    int64_t id;
    Published pub;
    ASSERT_TRUE(read_all(fds[0], &id, sizeof id));
    ASSERT_TRUE(read_all(fds[0], &pub, sizeof pub));
    before[id] = pub;
  }
  ::close(fds[0]);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) << status;
  ASSERT_GT(before.size(), 30u);
  EXPECT_GE(closures, 1) << "the drive should have closed a loop";

  NodeHarness h(p);
  const auto report = h.adapter->recovery();
  ASSERT_TRUE(report.has_value());
  EXPECT_TRUE(report->damage.empty()) << report->damage;
  EXPECT_GT(report->snapshot_scans, 0u);
  EXPECT_EQ(report->scans, before.size());
  const auto& nodes = h.adapter->mapper().nodes();
  ASSERT_EQ(nodes.size(), before.size());
  int64_t newest_id = 0;
  for (const auto& node : nodes) {
    const auto it = before.find(node.scan.scan_id);
    ASSERT_NE(it, before.end()) << "scan " << node.scan.scan_id << " was never published";
    // What consumers were last told about this scan is what the state remembers.
    EXPECT_EQ(node.revision, it->second.revision) << node.scan.scan_id;
    EXPECT_NEAR(node.published.x(), it->second.x, 1e-6);
    EXPECT_NEAR(node.published.y(), it->second.y, 1e-6);
    newest_id = std::max(newest_id, node.scan.scan_id);
  }
  EXPECT_EQ(h.adapter->scan_ids().last_issued, newest_id);

  // The laser driver restarted too: its ids count from 1 again. Published ids must not.
  drive(h, 230, 260, 1000, -230);
  const auto after = h.published<aligned_scan_t>("ALIGNED_SCAN");
  ASSERT_FALSE(after.empty());
  std::set<int64_t> fresh;
  for (const auto& a : after)
    if (a.revision == 0) {
      EXPECT_GT(a.scan_id, newest_id);
      EXPECT_TRUE(fresh.insert(a.scan_id).second) << "id " << a.scan_id << " repeated";
    }
  EXPECT_GT(fresh.size(), 3u);
}

// Files as a SIGKILL leaves them (copied while the node runs), then damaged: a torn last
// record and a flipped byte. Both are reported and cut off; what is loaded is an intact prefix.
TEST(ScanMapperPersistence, DamagedJournalTailIsReportedAndDropped)
{
  TempDir dir("torn");
  auto opts = sm::testing::node_test_options();
  opts.loop.enabled = false;  // every record is one scan
  const auto p = persistence(dir.path / "live", 100000);
  NodeHarness h(p, opts);
  drive(h, 0, 80);
  std::vector<int64_t> ids;
  for (const auto& a : h.published<aligned_scan_t>("ALIGNED_SCAN")) ids.push_back(a.scan_id);
  ASSERT_GT(ids.size(), 15u);
  const auto journal = p.state_file + ".journal";

  const auto damaged_copy = [&](const std::string& name, const std::function<void(const fs::path&)>& damage) {
    const fs::path d = dir.path / name;
    fs::create_directories(d);
    if (fs::exists(p.state_file)) fs::copy_file(p.state_file, d / "state.bin");
    fs::copy_file(journal, d / "state.bin.journal");
    damage(d / "state.bin.journal");
    return persistence(d, 100000);
  };
  {
    const auto torn = damaged_copy("torn", [](const fs::path& j) { fs::resize_file(j, fs::file_size(j) - 10); });
    NodeHarness r(torn, opts);
    const auto rep = *r.adapter->recovery();
    EXPECT_NE(rep.damage.find("torn"), std::string::npos) << rep.damage;
    ASSERT_EQ(rep.scans, ids.size() - 1);  // the torn record, and only it, is gone
    for (size_t i = 0; i < rep.scans; ++i) EXPECT_EQ(r.adapter->mapper().nodes()[i].scan.scan_id, ids[i]);
    // Compacted: a second start finds a clean state with the same scans.
  }
  {
    const auto again = persistence(dir.path / "torn", 100000);
    NodeHarness r(again, opts);
    EXPECT_TRUE(r.adapter->recovery()->damage.empty()) << r.adapter->recovery()->damage;
    EXPECT_EQ(r.adapter->recovery()->scans, ids.size() - 1);
    // The next scan gets an id no published scan had.
    drive(r, 80, 90);
    const auto pubs = r.published<aligned_scan_t>("ALIGNED_SCAN");
    ASSERT_FALSE(pubs.empty());
    EXPECT_GT(pubs.front().scan_id, ids.back());
  }
  {
    const auto flipped = damaged_copy("flip", [](const fs::path& j) {
      std::fstream f(j, std::ios::in | std::ios::out | std::ios::binary);
      f.seekp(static_cast<std::streamoff>(fs::file_size(j) / 2));
      f.put('\x5a');
    });
    NodeHarness r(flipped, opts);
    const auto rep = *r.adapter->recovery();
    EXPECT_FALSE(rep.damage.empty());  // CRC mismatch, or a bad header if the byte hit one
    ASSERT_GT(rep.scans, 0u);
    ASSERT_LT(rep.scans, ids.size());
    for (size_t i = 0; i < rep.scans; ++i) EXPECT_EQ(r.adapter->mapper().nodes()[i].scan.scan_id, ids[i]);
  }
}

TEST(ScanMapperPersistence, CorruptSnapshotIsKeptAsideAndTheMapStartsAfresh)
{
  TempDir dir("snap");
  const auto p = persistence(dir.path, 5);
  {
    NodeHarness h(p);
    drive(h, 0, 60);
  }  // clean stop: snapshot
  {
    std::fstream f(p.state_file, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(200);
    f.put('\x01');
  }
  NodeHarness h(p);
  const auto rep = *h.adapter->recovery();
  EXPECT_NE(rep.damage.find("snapshot refused"), std::string::npos) << rep.damage;
  EXPECT_EQ(rep.scans, 0u);
  EXPECT_TRUE(h.adapter->mapper().nodes().empty());
  EXPECT_TRUE(fs::exists(p.state_file + ".corrupt"));
}

// Issue 35: a snapshot of random bytes, an empty one and one cut off mid-content are refused
// naming the file, kept aside as found (.corrupt), and the map starts afresh; a journal of
// random bytes is reported naming it, kept as found (.damaged) and not replayed.
TEST(ScanMapperPersistence, BadSnapshotOrJournalFilesAreReportedKeptAsideAndNotLoaded)
{
  TempDir ref("badref");
  std::string valid;
  {
    const auto p = persistence(ref.path, 5);
    {
      NodeHarness h(p);
      drive(h, 0, 30);
    }  // clean stop: snapshot
    valid = rgnav::testing::read_file(p.state_file);
  }
  ASSERT_GT(valid.size(), 100u);
  TempDir bad("badfiles");
  for (const auto& f : rgnav::testing::write_bad_files(bad.path.string(), "snapshot", valid)) {
    SCOPED_TRACE(f.kind);
    TempDir dir("bad_" + f.kind);
    const auto p = persistence(dir.path, 5);
    fs::copy_file(f.path, p.state_file);
    NodeHarness h(p);
    const auto rep = *h.adapter->recovery();
    EXPECT_NE(rep.damage.find("snapshot refused (" + p.state_file + ": "), std::string::npos) << rep.damage;
    EXPECT_EQ(rep.scans, 0u);
    EXPECT_TRUE(h.adapter->mapper().nodes().empty());
    EXPECT_EQ(rgnav::testing::read_file(p.state_file + ".corrupt"), rgnav::testing::read_file(f.path));
  }
  TempDir dir("bad_journal");
  const auto p = persistence(dir.path, 5);
  const std::string junk = rgnav::testing::random_bytes(4096);
  rgnav::testing::write_bytes(p.state_file + ".journal", junk);
  NodeHarness h(p);
  const auto rep = *h.adapter->recovery();
  EXPECT_NE(rep.damage.find("journal " + p.state_file + ".journal: bad record header at byte 0"), std::string::npos)
      << rep.damage;
  EXPECT_EQ(rep.scans, 0u);
  EXPECT_EQ(rgnav::testing::read_file(p.state_file + ".journal.damaged"), junk);
}

TEST(ScanMapperPersistence, JournalRecordsAreNotReplayedTwiceAfterASnapshot)
{
  // A crash between writing a snapshot and emptying the journal: the journal's records are
  // all in the snapshot already and must be skipped, not appended again.
  TempDir dir("twice");
  auto opts = sm::testing::node_test_options();
  opts.loop.enabled = false;
  const auto p = persistence(dir.path, 100000);
  size_t scans = 0;
  std::string journal_copy;
  {
    NodeHarness h(p, opts);
    drive(h, 0, 60);
    scans = h.adapter->mapper().nodes().size();
    std::ifstream in(p.state_file + ".journal", std::ios::binary);
    journal_copy.assign(std::istreambuf_iterator<char>(in), {});
  }  // clean stop: snapshot of everything, journal emptied
  ASSERT_FALSE(journal_copy.empty());
  std::ofstream(p.state_file + ".journal", std::ios::binary) << journal_copy;
  NodeHarness h(p, opts);
  EXPECT_TRUE(h.adapter->recovery()->damage.empty()) << h.adapter->recovery()->damage;
  EXPECT_EQ(h.adapter->recovery()->records_replayed, 0u);
  EXPECT_EQ(h.adapter->mapper().nodes().size(), scans);
}
