// loop_canary: a bare periodic loop (the lld's PeriodicLoop with nothing in its step: no bus,
// no allocation, no locks) for deploy/bench/control.sh. It runs beside the lld, pinned to one
// CPU, at the lld's real-time priority, and records its stalls with their CLOCK_MONOTONIC
// times. A stall of the lld that a canary saw at the same moment came from outside the lld
// (the scheduler, or the host not running the virtual CPU); one that no canary saw is the
// lld's own.
#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <csignal>
#include <thread>

#include "lld/loop_stats_json.h"
#include "lld/periodic_loop.h"
#include "runtime/realtime.h"

namespace {
rgnav::lld::PeriodicLoop* g_loop = nullptr;  // for the signal handler only
void on_signal(int) { if (g_loop) g_loop->stop(); }
}  // namespace

int main(int argc, char** argv)
{
  CLI::App app("loop_canary");
  double period_ms = 1.0, seconds = 60.0, stall_ms = 2.0;
  int priority = 40;
  std::string out;
  app.add_option("--period-ms", period_ms)->check(CLI::Range(0.1, 1000.0));
  app.add_option("--seconds", seconds, "run this long (or until SIGTERM/SIGINT)")->check(CLI::Range(0.0, 86400.0));
  app.add_option("--stall-ms", stall_ms, "a wake this late after its deadline is a stall")->check(CLI::Range(0.01, 1000.0));
  app.add_option("--priority", priority, "SCHED_FIFO priority (0: normal scheduling)")->check(CLI::Range(0, 99));
  app.add_option("--out", out, "stats JSON")->required();
  CLI11_PARSE(app, argc, argv);

  rgnav::lld::PeriodicLoop loop(std::chrono::nanoseconds(static_cast<int64_t>(period_ms * 1e6)), stall_ms, 512);
  g_loop = &loop;
  std::signal(SIGTERM, on_signal);
  std::signal(SIGINT, on_signal);
  bool granted = false;
  const std::string what = rgnav::runtime::request_realtime(priority, true, &granted);
  if (!granted) spdlog::warn("loop_canary: {}", what);
  const int64_t end = rgnav::lld::monotonic_ns() + static_cast<int64_t>(seconds * 1e9);
  rgnav::lld::PeriodicLoop::Tick tick;
  while (loop.wait(&tick) && rgnav::lld::monotonic_ns() < end) {
  }
  return rgnav::lld::write_loop_stats(out, loop.stats()) ? 0 : 1;
}
