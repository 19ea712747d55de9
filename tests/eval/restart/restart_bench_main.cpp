// rg_kernel_restart_bench: how long an RG kernel takes to restart after a long run, with the
// journal alone (snapshot_every_inputs = 0: every input since the start is replayed, as before
// snapshots existed) and with periodic snapshots (load the newest + replay the journal tail).
// A synthetic robot drives back and forth between two furnished rooms through a door for
// --minutes of message time, an aligned scan every --scan-period (the scan mapper's gate:
// 0.2 m of travel at 0.4 m/s gives one every 0.5 s), a gateway event at each door crossing.
// The snapshot run is stopped at the worst moment, --tail inputs after its last snapshot (by
// default one input before the next would be taken). Prints figures only; nothing is asserted
// (timings depend on the machine).
//
//   build-rgk/bin/rg_kernel_restart_bench --minutes 20 --dir /tmp/rgk_bench
// leaves DIR/journal_only_at_stop and DIR/snapshots_at_stop: the state folders at the stop, for
// timing a real `rg_kernel --state-dir` start on them.
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <random>

#include "fake_bus_node.h"
#include "kernel_messages.h"
#include "procs/rg_kernel/rg_kernel_node.h"
#include "rgmap/rgmap_json.h"

using namespace rgnav;
using namespace rgnav::rg_kernel;
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

struct Input
{
  std::string channel;
  std::vector<uint8_t> bytes;
};

std::vector<Input> synthetic_run(double minutes, double scan_period_s)
{
  auto walls = rg_kernel::testing::two_rooms();
  for (const auto& w : rg_kernel::testing::box(1.6, 2.2, 2.4, 2.6)) walls.push_back(w);
  for (const auto& w : rg_kernel::testing::box(5.5, 0.0, 6.5, 0.5)) walls.push_back(w);
  const std::vector<rg_kernel::testing::Pillar> pillars = {{{3.2, 0.7}, 0.12}};
  std::mt19937 rng(42);
  std::normal_distribution<double> jitter(0.0, 1.0);
  std::vector<Input> out;
  int64_t t = 1'000'000, id = 1;
  const int64_t end = t + static_cast<int64_t>(minutes * 60e6), dt = static_cast<int64_t>(scan_period_s * 1e6);
  auto scan = [&](double x, double y, double th) {
    t += dt;
    pose2d_t pose;
    pose.x = x + 0.02 * jitter(rng);
    pose.y = y + 0.02 * jitter(rng);
    pose.theta = th + 0.01 * jitter(rng);
    const aligned_scan_t m =
        rg_kernel::testing::aligned_scan_msg(walls, t, id++, pose, pillars, [&] { return 0.005 * jitter(rng); });
    std::vector<uint8_t> buf;
    std::string why;
    if (!bus::encode(m, &buf, &why)) throw std::runtime_error(why);
    out.push_back({"ALIGNED_SCAN", std::move(buf)});
  };
  auto door = [&](double x, double heading) {
    t += 1000;
    const gateway_event_t e = rg_kernel::testing::door_traversed_msg(t, id - 1, id, x, heading);
    std::vector<uint8_t> buf;
    std::string why;
    if (!bus::encode(e, &buf, &why)) throw std::runtime_error(why);
    out.push_back({"GATEWAY_EVENTS", std::move(buf)});
  };
  while (t < end) {
    for (double x = 0.8; x < 3.8 && t < end; x += 0.2) scan(x, 1.5, 0);
    door(4.3, 0);
    for (double x = 4.4; x < 7.4 && t < end; x += 0.2) scan(x, 1.5, 0);
    for (double th = 0.3; th < M_PI && t < end; th += 0.3) scan(7.4, 1.5, th);
    for (double x = 7.4; x > 4.4 && t < end; x -= 0.2) scan(x, 1.6, M_PI);
    door(3.7, M_PI);
    for (double x = 3.6; x > 0.8 && t < end; x -= 0.2) scan(x, 1.6, M_PI);
    for (double th = M_PI - 0.3; th > 0 && t < end; th -= 0.3) scan(0.8, 1.5, th);
  }
  return out;
}

struct Process : rgnav::testing::FakeBusNode
{
  Process(const std::string& dir, int64_t snapshot_every, int sync_every) : FakeBusNode("rg_kernel")
  {
    NodeConfig c;
    c.state_dir = dir;
    c.snapshot_every_inputs = snapshot_every;
    c.sync_every_inputs = sync_every;
    kernel = std::make_unique<RgKernelNode>(*node, c);
  }
  std::string map_json() { return rgmap::to_json(const_cast<RgKernel&>(kernel->kernel()).refreshed_map()).dump(); }
  std::unique_ptr<RgKernelNode> kernel;
};

uintmax_t folder_bytes(const std::string& dir)
{
  uintmax_t n = 0;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_regular_file()) n += e.file_size();
  return n;
}

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

}  // namespace

int main(int argc, char** argv)
{
  CLI::App app{"RG kernel restart time after a long synthetic run, journal only vs. snapshots"};
  double minutes = 20, scan_period = 0.5;
  int64_t snapshot_every = NodeConfig{}.snapshot_every_inputs;
  int sync_every = NodeConfig{}.sync_every_inputs;
  std::string dir = (fs::temp_directory_path() / "rgk_restart_bench").string();
  app.add_option("--minutes", minutes, "message time of the run")->check(CLI::Range(0.1, 600.0));
  app.add_option("--scan-period", scan_period, "[s] between aligned scans")->check(CLI::Range(0.05, 10.0));
  app.add_option("--snapshot-every", snapshot_every, "inputs between snapshots in the 'after' run");
  app.add_option("--sync-every", sync_every, "group commit: inputs per fsync");
  int64_t tail = -1;
  bool only_snapshots = false;
  app.add_flag("--only-snapshots", only_snapshots, "skip the journal-only run");
  app.add_option("--tail", tail, "inputs after the last snapshot when stopping (default: snapshot-every - 1, the worst case)");
  app.add_option("--dir", dir, "scratch folder (emptied)");
  CLI11_PARSE(app, argc, argv);
  spdlog::set_level(spdlog::level::warn);
  if (tail < 0 || tail >= snapshot_every) tail = std::max<int64_t>(0, snapshot_every - 1);

  const auto inputs = synthetic_run(minutes, scan_period);
  std::printf("run: %.1f min of message time, %zu inputs (one scan every %.2f s)\n", minutes, inputs.size(), scan_period);
  std::string maps[2];
  for (int variant = only_snapshots ? 1 : 0; variant < 2; ++variant) {
    const bool snapshots = variant == 1;
    const std::string d = dir + (snapshots ? "/snapshots" : "/journal_only");
    fs::remove_all(d);
    const auto t0 = Clock::now();
    {
      Process p(d, snapshots ? snapshot_every : 0, sync_every);
      // The worst moment to stop: just before the next snapshot, the longest journal tail.
      const size_t last_snapshot_at = snapshots && static_cast<size_t>(tail) < inputs.size() ? inputs.size() - static_cast<size_t>(tail) : inputs.size();
      for (size_t k = 0; k < inputs.size(); ++k) {
        if (k == last_snapshot_at) p.kernel->snapshot_now();
        p.bus->publish(inputs[k].channel, inputs[k].bytes.data(), inputs[k].bytes.size());
      }
      p.kernel->store()->wait_snapshot();
      maps[variant] = p.map_json();
    }
    const double run_s = seconds_since(t0);
    // The folder as the stop left it, for measuring a real process restart on it.
    fs::remove_all(d + "_at_stop");
    fs::copy(d, d + "_at_stop", fs::copy_options::recursive);
    const auto t1 = Clock::now();
    Process restarted(d, snapshots ? snapshot_every : 0, sync_every);
    const double restart_s = seconds_since(t1);
    const bool same = restarted.map_json() == maps[variant];
    std::printf("%-13s run %.1f s; restart %.3f s: %lld inputs (%lld from snapshot generation %lld, %lld replayed from the journal); "
                "state folder %.1f MB; same map as before the stop: %s\n",
                snapshots ? "snapshots:" : "journal only:", run_s, restart_s, static_cast<long long>(restarted.kernel->restored_inputs()),
                static_cast<long long>(restarted.kernel->restored_inputs() - restarted.kernel->replayed_from_journal()),
                static_cast<long long>(restarted.kernel->snapshot_generation()),
                static_cast<long long>(restarted.kernel->replayed_from_journal()), folder_bytes(d) / 1e6, same ? "yes" : "NO");
    if (snapshots) {
      const auto t2 = Clock::now();
      restarted.kernel->snapshot_now();
      std::printf("%-13s one snapshot (serialise + write + fsync + rename) %.3f s\n", "", seconds_since(t2));
    }
  }
  if (only_snapshots) return 0;
  std::printf("journal-only and snapshot runs give the same map: %s\n", maps[0] == maps[1] ? "yes" : "NO");
  return maps[0] == maps[1] ? 0 : 1;
}
