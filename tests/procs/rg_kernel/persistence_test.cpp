// The RG kernel's promise: a SIGKILL at any instant followed by a restart yields the map of
// every input acknowledged before the kill. A kill can only leave the journal cut at some
// byte; these tests cut it at many bytes and compare the restarted map with the reference.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "bad_files.h"
#include "fake_bus_node.h"
#include "kernel_messages.h"
#include "persist/atomic_file.h"
#include "persist/journal.h"
#include "procs/rg_kernel/rg_kernel_conversions.h"
#include "procs/rg_kernel/rg_kernel_node.h"
#include "rgmap/rgmap_conversions.h"
#include "rgmap/rgmap_json.h"
#include "rgmap/saved_map.h"
#include "rgnav/region_name_t.hpp"

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

struct KernelProcess : rgnav::testing::FakeBusNode
{
  explicit KernelProcess(const std::string& dir, int64_t snapshot_every = 0) : FakeBusNode("rg_kernel")
  {
    NodeConfig c;
    c.state_dir = dir;
    c.sync_every_inputs = 100000;  // the test cuts the files itself; fsync only slows it down
    c.sync_period_s = 10.0;
    c.snapshot_every_inputs = snapshot_every;
    kernel = std::make_unique<RgKernelNode>(*node, c);
  }
  std::string map_json() { return rgmap::to_json(const_cast<RgKernel&>(kernel->kernel()).refreshed_map()).dump(); }
  std::unique_ptr<RgKernelNode> kernel;
};

std::vector<std::pair<std::string, std::vector<uint8_t>>> inputs()
{
  std::vector<std::pair<std::string, std::vector<uint8_t>>> out;
  const auto walls = testing::two_rooms();
  int64_t t = 1'000'000, id = 1;
  auto scan = [&](double x, double th) {
    t += 200'000;
    const aligned_scan_t m = testing::aligned_scan_msg(walls, t, id++, pose2d_t{x, 1.5, th});
    std::vector<uint8_t> buf;
    std::string why;
    EXPECT_TRUE(bus::encode(m, &buf, &why)) << why;
    out.push_back({"ALIGNED_SCAN", buf});
  };
  for (double x = 1.0; x < 3.9; x += 0.3) scan(x, 0);
  t += 1000;
  const gateway_event_t e = testing::door_traversed_msg(t, id - 1, 7, 4.3, 0.0);
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
      journal_size.push_back(fs::file_size(ref.kernel->store()->journal_path(0)));
    }
  }
  // Without snapshots everything is in generation 0.
  std::ifstream jin(dir + "/inputs.0000000000.journal", std::ios::binary);
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

class RestartContinues : public ::testing::TestWithParam<int64_t>
{
};

TEST_P(RestartContinues, AsIfUninterrupted)
{
  const int64_t snapshot_every = GetParam();
  const auto in = inputs();
  const std::string whole = fresh_dir("whole"), split = fresh_dir("split");
  std::string expected;
  {
    KernelProcess p(whole, snapshot_every);
    for (const auto& [ch, b] : in) p.bus->publish(ch, b.data(), b.size());
    expected = p.map_json();
  }
  {
    KernelProcess first(split, snapshot_every);
    for (size_t k = 0; k < in.size() / 2; ++k) first.bus->publish(in[k].first, in[k].second.data(), in[k].second.size());
  }
  KernelProcess second(split, snapshot_every);
  if (snapshot_every > 0) {
    EXPECT_GT(second.kernel->snapshot_generation(), 0);
  }
  for (size_t k = in.size() / 2; k < in.size(); ++k) second.bus->publish(in[k].first, in[k].second.data(), in[k].second.size());
  EXPECT_EQ(second.map_json(), expected);
  // And it published what it restored, with a checkpoint on disk that loads.
  EXPECT_FALSE(second.bus->published_on("RG_MAP").empty());
  second.kernel->publish();
  // A clean stop leaves the final map in rgmap.json, the export tools read.
  second.kernel.reset();
  EXPECT_EQ(rgmap::to_json(rgmap::load_saved_map(split + "/rgmap.json")).dump(), expected);
}

INSTANTIATE_TEST_SUITE_P(RgKernelPersistence, RestartContinues, ::testing::Values(0, 3));

// The operator's REGION_NAME: published at once in a new map version, journaled like any input
// (so a restart keeps it), and refused without a trace when it names nothing or is not a name.
TEST(RgKernelPersistence, RegionNamesArePublishedJournaledAndRefusedWhenBad)
{
  const auto in = inputs();
  const std::string dir = fresh_dir("names");
  const auto name = [](KernelProcess& p, int64_t region, const std::string& n) {
    region_name_t m;
    m.utime = 1'700'000'000'000'000;   // an operator's wall time, far from the scans' time
    m.region_id = region;
    m.name = n;
    std::vector<uint8_t> buf(static_cast<size_t>(m.getEncodedSize()));
    m.encode(buf.data(), 0, static_cast<int>(buf.size()));
    p.bus->publish("REGION_NAME", buf.data(), buf.size());
  };
  const auto last_map = [](KernelProcess& p) {
    const auto maps = rgnav::testing::decoded<rg_map_t>(*p.bus, "RG_MAP");
    return maps.empty() ? rgmap::RgMap() : rgmap::from_msg(maps.back());
  };
  int64_t version = 0;
  {
    KernelProcess p(dir);
    for (const auto& [ch, b] : in) p.bus->publish(ch, b.data(), b.size());
    ASSERT_GE(p.kernel->kernel().map().regions().size(), 2u);
    version = p.kernel->kernel().map().version;
    const size_t published = p.bus->published_on("RG_MAP").size();
    name(p, 2, "lab");
    ASSERT_EQ(p.bus->published_on("RG_MAP").size(), published + 1);
    const rgmap::RgMap m = last_map(p);
    EXPECT_EQ(m.version, version + 1);
    EXPECT_EQ(m.region(2)->name, "lab");
    // The same name again changes nothing; bad ones are dropped and counted.
    name(p, 2, "lab");
    name(p, 99, "hall");          // no such region
    name(p, 1, "LAB");            // region 2's name already
    name(p, 1, std::string("room") + char(1));   // a control character (semantic check)
    name(p, 1, "hall east");     // fine
    name(p, 1, "");               // empty (semantic check)
    EXPECT_EQ(p.node->drops().on_channel("REGION_NAME"), 4);
    EXPECT_EQ(p.kernel->kernel().map().region(1)->name, "hall east");
    version = p.kernel->kernel().map().version;
  }
  // A restart replays the names with the scans.
  KernelProcess again(dir);
  EXPECT_EQ(again.kernel->kernel().map().version, version);
  EXPECT_EQ(again.kernel->kernel().map().region(2)->name, "lab");
  EXPECT_EQ(again.kernel->kernel().map().region(1)->name, "hall east");
  EXPECT_EQ(last_map(again).region(2)->name, "lab");
}

std::vector<std::string> files_in(const std::string& dir)
{
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) out.push_back(e.path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}

TEST(RgKernelPersistence, SnapshotRestoresTheKernelExactly)
{
  std::vector<ScanInput> scans;
  std::vector<GatewayEventInput> events;
  std::vector<bool> is_scan;
  for (const auto& [ch, b] : inputs()) {
    if (ch == "ALIGNED_SCAN") {
      aligned_scan_t m;
      std::string why;
      ASSERT_TRUE(bus::decode(b.data(), b.size(), &m, &why));
      scans.push_back(to_input(m));
    } else {
      gateway_event_t m;
      std::string why;
      ASSERT_TRUE(bus::decode(b.data(), b.size(), &m, &why));
      events.push_back(to_input(m));
    }
    is_scan.push_back(ch == "ALIGNED_SCAN");
  }
  RgKernel a{KernelOptions{}}, b{KernelOptions{}};
  size_t si = 0, ei = 0;
  auto feed = [&](RgKernel& k, size_t i, size_t& s, size_t& e) {
    if (is_scan[i]) k.add_scan(scans[s++]);
    else k.add_gateway_event(events[e++]);
  };
  const size_t half = is_scan.size() / 2 + 1;   // past the door: two regions, one finalised
  for (size_t i = 0; i < half; ++i) feed(a, i, si, ei);
  const std::string snap = a.snapshot();
  b.restore(snap);
  EXPECT_EQ(b.snapshot(), snap);
  size_t sb = si, eb = ei;
  for (size_t i = half; i < is_scan.size(); ++i) {
    feed(a, i, si, ei);
    feed(b, i, sb, eb);
  }
  EXPECT_EQ(b.snapshot(), a.snapshot());
  EXPECT_EQ(rgmap::to_json(b.described_map()).dump(), rgmap::to_json(a.described_map()).dump());
  // Damaged bytes are refused and leave the kernel as it was.
  RgKernel c{KernelOptions{}};
  EXPECT_THROW(c.restore(snap.substr(0, snap.size() / 2)), persist::CorruptBytes);
  EXPECT_THROW(c.restore(snap + "x"), persist::CorruptBytes);
  EXPECT_THROW(c.restore("garbage"), persist::CorruptBytes);
  EXPECT_EQ(c.map().regions().size(), 0u);
}

// A SIGKILL can stop the kernel between any two records, with snapshots being taken: the
// state folder as it is then (including a half-written snapshot temp file, or a record torn
// half-way) restarts to the map of every input journaled.
TEST(RgKernelPersistence, KillAtEveryRecordWithSnapshots)
{
  const auto in = inputs();
  const std::string dir = fresh_dir("snapref");
  std::vector<std::string> map_after = {""};
  std::vector<std::string> copies = {""};
  {
    KernelProcess ref(dir, 4);
    map_after[0] = ref.map_json();
    for (size_t k = 0; k < in.size(); ++k) {
      ref.bus->publish(in[k].first, in[k].second.data(), in[k].second.size());
      ref.kernel->store()->wait_snapshot();
      map_after.push_back(ref.map_json());
      const std::string copy = fresh_dir("kill" + std::to_string(k + 1));
      fs::copy(dir, copy, fs::copy_options::recursive | fs::copy_options::overwrite_existing);
      copies.push_back(copy);
    }
    EXPECT_GE(ref.kernel->store()->generation(), 4);
  }
  for (size_t k = 1; k < copies.size(); ++k) {
    // A snapshot writer killed before its rename leaves a temp file: ignored.
    std::ofstream(copies[k] + "/kernel.0000000099.snapshot.tmp") << "rgnav-checked-file v1 length=100";
    {
      KernelProcess restarted(copies[k], 4);
      EXPECT_EQ(restarted.map_json(), map_after[k]) << "killed after input " << k;
      EXPECT_EQ(restarted.kernel->restored_inputs(), static_cast<int64_t>(k));
      EXPECT_LE(restarted.kernel->replayed_from_journal(), 4 + 1) << "the journal tail is bounded";
      EXPECT_TRUE(restarted.kernel->store()->problems().empty());
    }
    // Torn last record of the newest journal: the map of the inputs before it.
    const auto journals = files_in(copies[k]);
    std::string newest;
    for (const auto& f : journals)
      if (f.rfind("inputs.", 0) == 0 && f.size() > 8 && f.substr(f.size() - 8) == ".journal") newest = f;
    ASSERT_FALSE(newest.empty());
    const auto size = fs::file_size(copies[k] + "/" + newest);
    if (size == 0) continue;   // just rotated: the last input is in a snapshot already
    fs::resize_file(copies[k] + "/" + newest, size - 5);
    KernelProcess torn(copies[k], 4);
    EXPECT_EQ(torn.map_json(), map_after[k - 1]) << "torn record after input " << k;
    EXPECT_EQ(torn.kernel->restored_inputs(), static_cast<int64_t>(k - 1));
    EXPECT_FALSE(torn.kernel->store()->tail_damage().empty());   // the cut tail is reported
    EXPECT_TRUE(torn.kernel->store()->problems().empty());       // ... as the trace of a kill, not a loss
  }
  for (size_t k = 1; k < copies.size(); ++k) fs::remove_all(copies[k]);
}

TEST(RgKernelPersistence, DamagedSnapshotIsReportedNeverLoadedAndThePreviousOneUsed)
{
  const auto in = inputs();
  const std::string dir = fresh_dir("corrupt");
  std::string expected;
  {
    KernelProcess p(dir, 5);
    // Each snapshot written before the next input: a snapshot falls due only while none is being
    // written, so on a loaded machine a slow writer would otherwise leave a single generation.
    for (const auto& [ch, b] : in) {
      p.bus->publish(ch, b.data(), b.size());
      p.kernel->store()->wait_snapshot();
    }
    expected = p.map_json();
  }
  std::vector<int64_t> gens;
  {
    StateStore s({dir});
    gens = s.snapshot_generations();
  }
  ASSERT_GE(gens.size(), 2u);
  ASSERT_LE(gens.size(), 2u) << "older snapshots are removed once a newer one is durable";
  const std::string pristine = fresh_dir("pristine");
  fs::copy(dir, pristine, fs::copy_options::recursive | fs::copy_options::overwrite_existing);

  auto newest_path = [&](const std::string& d) {
    char name[64];
    std::snprintf(name, sizeof name, "/kernel.%010lld.snapshot", static_cast<long long>(gens[0]));
    return d + name;
  };
  // 1. A flipped byte (CRC), 2. a truncated file, 3. a payload that passes the CRC but is not
  // a kernel state, 4. random bytes, 5. an empty file: each is reported, renamed *.corrupt, and
  // the previous snapshot plus its longer journal tail give the same map.
  for (int kind = 0; kind < 5; ++kind) {
    const std::string d = fresh_dir("damaged" + std::to_string(kind));
    fs::copy(pristine, d, fs::copy_options::recursive | fs::copy_options::overwrite_existing);
    const std::string path = newest_path(d);
    if (kind == 0) {
      std::fstream f(path, std::ios::binary | std::ios::in | std::ios::out);
      f.seekp(static_cast<std::streamoff>(fs::file_size(path) / 2));
      f.put('\x5a');
    } else if (kind == 1) {
      fs::resize_file(path, fs::file_size(path) - 100);
    } else if (kind == 2) {
      persist::write_atomically(path, "not a kernel state");
    } else {
      rgnav::testing::write_bytes(path, kind == 3 ? rgnav::testing::random_bytes(4096) : "");
    }
    KernelProcess restarted(d, 5);
    EXPECT_EQ(restarted.map_json(), expected) << "damage kind " << kind;
    EXPECT_EQ(restarted.kernel->snapshot_generation(), gens[1]);
    EXPECT_EQ(restarted.kernel->restored_inputs(), static_cast<int64_t>(in.size()));
    ASSERT_FALSE(restarted.kernel->store()->problems().empty());
    EXPECT_NE(restarted.kernel->store()->problems()[0].find("snapshot"), std::string::npos);
    EXPECT_TRUE(fs::exists(path + ".corrupt"));
    EXPECT_FALSE(fs::exists(path));
  }
  // Both snapshots damaged and the journals before them gone: refuse, never a different map.
  const std::string d = fresh_dir("hopeless");
  fs::copy(pristine, d, fs::copy_options::recursive | fs::copy_options::overwrite_existing);
  for (const auto& f : files_in(d))
    if (f.size() > 9 && f.substr(f.size() - 9) == ".snapshot") persist::write_atomically(d + "/" + f, "x");
  ASSERT_FALSE(fs::exists(d + "/inputs.0000000000.journal"));
  EXPECT_THROW(KernelProcess hopeless(d, 5), std::runtime_error);
}

TEST(RgKernelPersistence, DamagedOlderJournalEndsTheReplayThereAndIsReported)
{
  const auto in = inputs();
  const std::string dir = fresh_dir("olderjournal");
  std::vector<std::string> map_after;
  {
    KernelProcess p(dir, 4);
    map_after.push_back(p.map_json());
    for (size_t k = 0; k < 6; ++k) {
      p.bus->publish(in[k].first, in[k].second.data(), in[k].second.size());
      p.kernel->store()->wait_snapshot();
      map_after.push_back(p.map_json());
    }
  }
  // One snapshot (generation 1, after 4 inputs); journal 0 holds inputs 1-4, journal 1 inputs 5-6.
  ASSERT_TRUE(fs::exists(dir + "/kernel.0000000001.snapshot"));
  fs::remove(dir + "/kernel.0000000001.snapshot");   // lost: generation 0 is the way back
  {
    // Flip a byte inside the third record of journal 0.
    const std::string j0 = dir + "/inputs.0000000000.journal";
    persist::Journal probe(j0, false);
    ASSERT_EQ(probe.recovered().size(), 4u);
    const size_t at = 2 * (16 + probe.recovered()[0].bytes.size()) + 16 + 10;   // scans encode to the same size
    ASSERT_EQ(probe.recovered()[0].bytes.size(), probe.recovered()[1].bytes.size());
    std::fstream f(j0, std::ios::binary | std::ios::in | std::ios::out);
    f.seekp(static_cast<std::streamoff>(at));
    f.put('\x77');
  }
  KernelProcess restarted(dir, 4);
  EXPECT_EQ(restarted.map_json(), map_after[2]);   // inputs after the damage cannot be applied
  EXPECT_EQ(restarted.kernel->restored_inputs(), 2);
  ASSERT_EQ(restarted.kernel->store()->problems().size(), 2u);
  EXPECT_NE(restarted.kernel->store()->problems()[0].find("CRC"), std::string::npos);
  EXPECT_TRUE(fs::exists(dir + "/inputs.0000000001.journal.orphaned"));
}

// Issue 35: a journal that holds no record at all (random bytes) is no torn tail: it is
// reported as a loss, kept as found (*.damaged), and the kernel starts from what was intact
// (here: nothing). An empty journal is a new one; a cut-off one is the trace of a kill.
TEST(RgKernelPersistence, JournalOfRandomBytesIsReportedKeptAsideAndNotReplayed)
{
  const std::string dir = fresh_dir("random_journal");
  const std::string fresh_map = KernelProcess(fresh_dir("random_journal_ref")).map_json();
  const std::string junk = rgnav::testing::random_bytes(4096);
  rgnav::testing::write_bytes(dir + "/inputs.0000000000.journal", junk);
  KernelProcess restarted(dir);
  EXPECT_EQ(restarted.map_json(), fresh_map);
  EXPECT_EQ(restarted.kernel->restored_inputs(), 0);
  ASSERT_EQ(restarted.kernel->store()->problems().size(), 1u);
  const std::string problem = restarted.kernel->store()->problems()[0];
  EXPECT_NE(problem.find(dir + "/inputs.0000000000.journal"), std::string::npos) << problem;
  EXPECT_NE(problem.find("bad record header at byte 0"), std::string::npos) << problem;
  EXPECT_EQ(rgnav::testing::read_file(dir + "/inputs.0000000000.journal.damaged"), junk);
  EXPECT_EQ(fs::file_size(dir + "/inputs.0000000000.journal"), 0u);   // new records start clean

  const std::string empty = fresh_dir("empty_journal");
  rgnav::testing::write_bytes(empty + "/inputs.0000000000.journal", "");
  KernelProcess from_empty(empty);
  EXPECT_EQ(from_empty.map_json(), fresh_map);
  EXPECT_TRUE(from_empty.kernel->store()->problems().empty());
  EXPECT_TRUE(from_empty.kernel->store()->tail_damage().empty());
}

TEST(RgKernelPersistence, GroupCommitSyncsBeforePublishing)
{
  const auto in = inputs();
  const std::string dir = fresh_dir("group");
  KernelProcess p(dir, 0);
  p.bus->publish(in[0].first, in[0].second.data(), in[0].second.size());
  p.bus->publish(in[1].first, in[1].second.data(), in[1].second.size());   // 0.2 s later: not yet published
  EXPECT_TRUE(p.kernel->store()->unsynced());
  p.kernel->publish();
  EXPECT_FALSE(p.kernel->store()->unsynced());
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

// Issue 35: random bytes, an empty file and a file cut off mid-record (AtomicFile: mid-payload).
TEST(AtomicFile, RefusesRandomBytesEmptyAndCutOffFilesNamingThem)
{
  const std::string d = fresh_dir("atomic_bad");
  persist::write_atomically(d + "/valid", std::string(200, 'v'));
  for (const auto& f : rgnav::testing::write_bad_files(d, "state", rgnav::testing::read_file(d + "/valid"))) {
    SCOPED_TRACE(f.kind);
    try {
      persist::read_checked(f.path);
      ADD_FAILURE() << f.path << " was read";
    } catch (const persist::CorruptFile& e) {
      EXPECT_EQ(std::string(e.what()).rfind(f.path + ": ", 0), 0u) << e.what();
    }
  }
}

TEST(Journal, RandomBytesAreKeptAsideEmptyIsNewCutOffIsATornTail)
{
  const std::string d = fresh_dir("journal_bad");
  {
    persist::Journal j(d + "/valid", false);
    j.append(1, "first");
    j.append(2, "second");
  }
  const std::string valid = rgnav::testing::read_file(d + "/valid");
  for (const auto& f : rgnav::testing::write_bad_files(d, "j", valid, valid.size() - 3)) {
    SCOPED_TRACE(f.kind);
    const std::string before = rgnav::testing::read_file(f.path);
    persist::Journal j(f.path, false);
    if (f.kind == "random") {
      EXPECT_TRUE(j.recovered().empty());
      EXPECT_TRUE(j.corrupt());
      EXPECT_NE(j.damage().find(f.path + ".damaged"), std::string::npos) << j.damage();
      EXPECT_EQ(rgnav::testing::read_file(f.path + ".damaged"), before);
    } else if (f.kind == "empty") {
      EXPECT_TRUE(j.recovered().empty());
      EXPECT_TRUE(j.damage().empty());
    } else {
      ASSERT_EQ(j.recovered().size(), 1u);
      EXPECT_EQ(j.recovered()[0].bytes, "first");
      EXPECT_NE(j.damage().find("torn"), std::string::npos) << j.damage();
      EXPECT_FALSE(j.corrupt());
      EXPECT_FALSE(fs::exists(f.path + ".damaged"));
    }
  }
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

TEST(RgKernelPersistence, OneKernelPerStateFolder)
{
  const std::string d = fresh_dir("folder_lock");
  StateStore first({d});
  try {
    StateStore second({d});
    ADD_FAILURE() << "a second store on " << d << " was opened";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), d + ": state folder is locked by another live rg_kernel");
  }
}

}  // namespace
}  // namespace rgnav::rg_kernel
