// A small rgnav process for exercising the supervisor and the fault harness for real: it
// subscribes to an input channel (optional), publishes on an output channel at a fixed rate,
// and owns state that must survive a restart — a counter (inputs accepted, or messages sent
// when it has no input) persisted atomically before each publication and reloaded at start.
// The counter goes out as velocity_cmd_t.seq, so anyone listening can check nothing was lost.
// With --work-ms it is also a busy process: every --work-every-ms its loop spends --work-ms in one
// step of work (progressing between steps only), as a scan mapper matching a scan would.
//   fault_probe --name mid --input FAULT_A --output FAULT_B --state /run/x/mid.state
#include <CLI/CLI.hpp>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>

#include "rgnav/velocity_cmd_t.hpp"
#include "runtime/process_main.h"
#include "time/message_time.h"

namespace {

struct ProbeFlags
{
  std::string input;
  std::string output;
  double rate_hz = 20;
  std::string state_path;
  int work_ms = 0;          // [ms] one step of work on the loop, 0 = none
  int work_every_ms = 1000;
};

class Probe
{
 public:
  Probe(rgnav::runtime::Node& node, ProbeFlags flags) : node_(node), flags_(std::move(flags))
  {
    count_ = load();
    if (!flags_.input.empty()) {
      // Counted at once, persisted when published: what went out (was acknowledged) is on disk
      // first, and a flood of inputs does not turn into a flood of file writes.
      node_.subscribe<rgnav::velocity_cmd_t>(flags_.input, [this](const rgnav::velocity_cmd_t&) { ++count_; });
    }
    if (!flags_.output.empty()) {
      node_.every(std::chrono::microseconds(static_cast<int64_t>(1e6 / flags_.rate_hz)), [this] { publish(); });
    }
    if (flags_.work_ms > 0)
      node_.every(std::chrono::milliseconds(flags_.work_every_ms), [this] { work(std::chrono::milliseconds(flags_.work_ms)); });
  }

 private:
  // Computes (spins on the CPU) for `d` without returning to the loop.
  static void work(std::chrono::milliseconds d)
  {
    const auto until = std::chrono::steady_clock::now() + d;
    volatile uint64_t turns = 0;
    while (std::chrono::steady_clock::now() < until) ++turns;
  }

  void publish()
  {
    if (flags_.input.empty()) ++count_;
    save();
    rgnav::velocity_cmd_t m;
    m.utime = rgnav::time::wall_utime();
    m.seq = count_;
    m.v = 0.1;
    m.omega = 0;
    m.deadline_us = 500000;
    m.source = node_.name();
    node_.publish(flags_.output, m);
  }

  int64_t load() const
  {
    if (flags_.state_path.empty()) return 0;
    std::ifstream in(flags_.state_path);
    int64_t v = 0;
    return (in >> v) ? v : 0;
  }

  void save() const
  {
    if (flags_.state_path.empty()) return;
    const std::string tmp = flags_.state_path + ".tmp";
    {
      std::ofstream out(tmp, std::ios::trunc);
      out << count_ << "\n";
    }
    std::rename(tmp.c_str(), flags_.state_path.c_str());
  }

  rgnav::runtime::Node& node_;
  ProbeFlags flags_;
  int64_t count_ = 0;
};

}  // namespace

int main(int argc, char** argv)
{
  ProbeFlags flags;
  return rgnav::runtime::process_main(
      argc, argv, "fault_probe",
      [&](rgnav::runtime::ProcessContext& ctx) { return std::make_shared<Probe>(ctx.node, flags); },
      [&](CLI::App& app) {
        app.add_option("--input", flags.input, "input channel (velocity_cmd_t)");
        app.add_option("--output", flags.output, "output channel (velocity_cmd_t, seq = state counter)");
        app.add_option("--rate", flags.rate_hz, "output rate [Hz]")->check(CLI::Range(0.1, 1000.0));
        app.add_option("--state", flags.state_path, "state file (persisted counter)");
        app.add_option("--work-ms", flags.work_ms, "one step of work on the loop this long [ms] (0: none)")->check(CLI::Range(0, 5000));
        app.add_option("--work-every-ms", flags.work_every_ms, "a step of work this often [ms]")->check(CLI::Range(10, 60000));
      });
}
