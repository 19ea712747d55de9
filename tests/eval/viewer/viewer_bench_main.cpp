// rgnav_viewer_bench (./rgnav bench viewer): the viewer process under a steady load, measured
// from outside. A publisher sends SLAM_POSE and LASER_FRONT at --rate-hz (stamped with the wall
// time of sending) and the two-room RG map once a second over udpm; --clients WebSocket clients
// read the viewer's stream. Measured: the delay from publishing a pose to a client holding its
// frame (p50/p95/max over every client; the browser's drawing is not included), the viewer's
// CPU (share of one core, from /proc over the measured window) and its resident memory at the
// start and end of the window, extrapolated linearly to 30 minutes when the window is shorter.
// Run in a private network namespace (deploy/bench/viewer.sh).
#include <CLI/CLI.hpp>
#include <unistd.h>

#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/websocket.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <fstream>
#include <iostream>
#include <mutex>
#include <sstream>
#include <thread>

#include "bus/lcm_bus.h"
#include "bus/typed.h"
#include "child_process.h"
#include "msg/conversions.h"
#include "rgmap/rgmap_conversions.h"
#include "rgnav/slam_pose_t.hpp"
#include "time/message_time.h"
#include "two_room_map.h"

namespace {

namespace beast = boost::beast;
namespace websocket = beast::websocket;
namespace net = boost::asio;
using tcp = net::ip::tcp;
using Clock = std::chrono::steady_clock;

struct ProcSample
{
  double cpu_s = 0;   // user + system
  double rss_mb = 0;
};

ProcSample sample(pid_t pid)
{
  ProcSample s;
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string text((std::istreambuf_iterator<char>(stat)), std::istreambuf_iterator<char>());
  // Fields after the command name (which may hold spaces) start after the last ')'.
  std::istringstream rest(text.substr(text.rfind(')') + 2));
  std::string field;
  long utime = 0, stime = 0;
  for (int i = 3; i <= 15 && rest >> field; ++i) {
    if (i == 14) utime = std::stol(field);
    if (i == 15) stime = std::stol(field);
  }
  s.cpu_s = static_cast<double>(utime + stime) / static_cast<double>(::sysconf(_SC_CLK_TCK));
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmRSS:", 0) == 0) s.rss_mb = std::stod(line.substr(6)) / 1024.0;
  }
  return s;
}

double percentile(std::vector<double> v, double p)
{
  if (v.empty()) return -1;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(p * static_cast<double>(v.size() - 1) + 0.5))];
}

}  // namespace

int main(int argc, char** argv)
{
  CLI::App app{"The viewer under load: message-to-client delay, CPU and memory."};
  std::string out, viewer_bin = RGNAV_VIEWER_BIN;
  double duration_s = 120, warmup_s = 5, rate_hz = 10;
  int clients = 3, port = 18036;
  app.add_option("--out", out, "JSON result file")->required();
  app.add_option("--duration", duration_s, "[s] measured window (after the warm-up)")->check(CLI::Range(5.0, 7200.0));
  app.add_option("--warmup", warmup_s, "[s] before measuring")->check(CLI::Range(1.0, 600.0));
  app.add_option("--rate-hz", rate_hz, "[Hz] poses and scans published")->check(CLI::Range(1.0, 100.0));
  app.add_option("--clients", clients, "WebSocket clients")->check(CLI::Range(1, 16));
  app.add_option("--port", port, "the viewer's port (in the bench's own network namespace)");
  app.add_option("--viewer", viewer_bin, "the viewer executable");
  CLI11_PARSE(app, argc, argv);

  rgnav::testing::ChildOptions co;
  co.stdout_path = out + ".viewer.log";
  co.stderr_path = out + ".viewer.log.stderr";
  rgnav::testing::ChildProcess viewer({viewer_bin, "--port", std::to_string(port)}, co);

  // The clients, once the viewer listens.
  std::mutex m;
  std::vector<double> latencies_ms;
  std::atomic<bool> measuring{false};
  std::atomic<int64_t> frames{0};
  std::atomic<int> connected{0};
  std::vector<std::thread> readers;
  for (int c = 0; c < clients; ++c) {
    readers.emplace_back([&] {
      net::io_context ioc;
      websocket::stream<tcp::socket> ws(ioc);
      for (int attempt = 0; attempt < 100; ++attempt) {
        try {
          tcp::resolver resolver(ioc);
          net::connect(ws.next_layer(), resolver.resolve("127.0.0.1", std::to_string(port)));
          ws.handshake("127.0.0.1", "/ws");
          break;
        } catch (const std::exception&) {
          beast::error_code ignored;
          ws.next_layer().close(ignored);
          std::this_thread::sleep_for(std::chrono::milliseconds(100));
        }
      }
      if (!ws.is_open()) return;
      ++connected;
      try {
        for (;;) {
          beast::flat_buffer b;
          ws.read(b);
          const int64_t now = rgnav::time::wall_utime();
          ++frames;
          const auto j = nlohmann::json::parse(beast::buffers_to_string(b.data()));
          if (j["type"] == "pose" && measuring) {
            std::lock_guard<std::mutex> lock(m);
            latencies_ms.push_back((now - j["utime"].get<int64_t>()) * 1e-3);
          }
        }
      } catch (const std::exception&) {
        // The viewer stopped: the end of the run.
      }
    });
  }

  rgnav::bus::LcmBus bus("");
  const auto world = rgnav::testing::two_room_world();
  const auto map_msg = rgnav::rgmap::to_msg(world.map);
  const rgnav::geometry::Pose2 base_from_laser(0.12, 0, 0);
  const auto start = Clock::now();
  const auto period = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / rate_hz));
  auto next = start;
  auto next_map = start;
  int64_t step = 0;
  ProcSample before{}, after{};
  bool started = false;
  const auto measure_from = start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(warmup_s));
  const auto end = measure_from + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(duration_s));
  while (Clock::now() < end) {
    std::this_thread::sleep_until(next);
    next += period;
    const auto now = Clock::now();
    if (!started && now >= measure_from) {
      before = sample(viewer.pid());
      measuring = true;
      started = true;
    }
    if (now >= next_map) {
      auto mm = map_msg;
      mm.utime = rgnav::time::wall_utime();
      rgnav::bus::publish(bus, "RG_MAP", mm);
      next_map += std::chrono::seconds(1);
    }
    // Back and forth along room_a.
    ++step;
    const double phase = std::fmod(step * 0.02, 2.0);
    const rgnav::geometry::Pose2 map_from_base(1.0 + 2.5 * (phase < 1 ? phase : 2 - phase), 1.5, phase < 1 ? 0 : M_PI);
    rgnav::slam_pose_t p{};
    p.utime = rgnav::time::wall_utime();
    p.scan_id = step;
    p.map_from_base = rgnav::msg::to_msg(map_from_base);
    p.map_from_odom = rgnav::msg::to_msg(rgnav::geometry::Pose2());
    rgnav::bus::publish(bus, "SLAM_POSE", p);
    rgnav::bus::publish(bus, "LASER_FRONT",
                        rgnav::msg::to_msg(rgnav::testing::cast_scan(world.walls, map_from_base, base_from_laser, p.utime, step)));
  }
  after = sample(viewer.pid());
  measuring = false;
  const auto status = viewer.stop();
  for (auto& t : readers) t.join();

  const double window_s = duration_s;
  const double growth = after.rss_mb - before.rss_mb;
  nlohmann::json j = {
      {"latency_ms_p50", percentile(latencies_ms, 0.50)},
      {"latency_ms_p95", percentile(latencies_ms, 0.95)},
      {"latency_ms_max", percentile(latencies_ms, 1.0)},
      {"latency_samples", latencies_ms.size()},
      {"latency_measured", "SLAM_POSE published over udpm -> its pose frame read by a WebSocket client; the browser's drawing not included"},
      {"cpu_core_share", (after.cpu_s - before.cpu_s) / window_s},
      {"clients", clients},
      {"clients_connected", connected.load()},
      {"updates_per_s", rate_hz},
      {"frames_received", frames.load()},
      {"rss_start_mb", before.rss_mb},
      {"rss_end_mb", after.rss_mb},
      {"rss_window_s", window_s},
      {"rss_growth_mb_30min", growth * 1800.0 / window_s},
      {"rss_growth_extrapolated", window_s < 1800.0},
      {"viewer_exit", status.describe()},
      {"targets", {{"latency_ms_p95", 200}, {"cpu_core_share", 0.05}, {"rss_growth_mb_30min", 0}}},
  };
  std::ofstream(out) << j.dump(2) << "\n";
  std::cout << j.dump(2) << std::endl;
  return connected.load() == clients && !latencies_ms.empty() ? 0 : 1;
}
