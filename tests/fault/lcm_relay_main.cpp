// An LCM relay that impairs what it forwards: loss, duplication and delay, for fault
// injection on a process's inputs (the kernel here has no netem). It forwards raw bytes,
// so it works for any message type. Impairment is off at start and toggled by SIGUSR1 (on)
// and SIGUSR2 (off), so it can sit in a launched stack and be switched by the harness.
//   lcm_relay --name relay_a --from FAULT_A --to FAULT_A_RELAYED --loss 0.3 --dup 0.2 --delay-ms 80
#include <CLI/CLI.hpp>
#include <signal.h>

#include <atomic>
#include <deque>
#include <random>
#include <vector>

#include "runtime/process_main.h"

namespace {

std::atomic<int> g_impair{0};
void on_usr(int sig) { g_impair = sig == SIGUSR1 ? 1 : 0; }

struct RelayFlags
{
  std::string from;
  std::string to;
  double loss = 0.0;
  double dup = 0.0;
  int delay_ms = 0;
  bool impair_at_start = false;
  uint32_t seed = 1;
};

class Relay
{
 public:
  using Clock = std::chrono::steady_clock;

  Relay(rgnav::runtime::Node& node, RelayFlags flags) : node_(node), flags_(std::move(flags)), rng_(flags_.seed)
  {
    g_impair = flags_.impair_at_start ? 1 : 0;
    struct sigaction sa{};
    sa.sa_handler = on_usr;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGUSR1, &sa, nullptr);
    sigaction(SIGUSR2, &sa, nullptr);
    // Raw: the relay must pass on (or impair) whatever arrives, valid or not.
    node_.bus().subscribe(flags_.from, [this](const rgnav::bus::RawMessage& m) { on_message(m); });
    node_.every(std::chrono::milliseconds(10), [this] { flush(); });  // delay resolution 10 ms
  }

 private:
  struct Held
  {
    Clock::time_point due;
    std::vector<uint8_t> data;
  };

  void on_message(const rgnav::bus::RawMessage& m)
  {
    std::vector<uint8_t> data(m.data, m.data + m.size);
    if (!g_impair) {
      node_.bus().publish(flags_.to, data.data(), data.size());
      return;
    }
    std::uniform_real_distribution<double> u(0.0, 1.0);
    if (u(rng_) < flags_.loss) return;
    const int copies = u(rng_) < flags_.dup ? 2 : 1;
    for (int i = 0; i < copies; ++i) held_.push_back({Clock::now() + std::chrono::milliseconds(flags_.delay_ms), data});
  }

  void flush()
  {
    const auto now = Clock::now();
    while (!held_.empty() && held_.front().due <= now) {
      node_.bus().publish(flags_.to, held_.front().data.data(), held_.front().data.size());
      held_.pop_front();
    }
  }

  rgnav::runtime::Node& node_;
  RelayFlags flags_;
  std::mt19937 rng_;
  std::deque<Held> held_;
};

}  // namespace

int main(int argc, char** argv)
{
  RelayFlags flags;
  return rgnav::runtime::process_main(
      argc, argv, "lcm_relay",
      [&](rgnav::runtime::ProcessContext& ctx) { return std::make_shared<Relay>(ctx.node, flags); },
      [&](CLI::App& app) {
        app.add_option("--from", flags.from, "channel to read")->required();
        app.add_option("--to", flags.to, "channel to write")->required();
        app.add_option("--loss", flags.loss, "probability a message is dropped")->check(CLI::Range(0.0, 1.0));
        app.add_option("--dup", flags.dup, "probability a message is sent twice")->check(CLI::Range(0.0, 1.0));
        app.add_option("--delay-ms", flags.delay_ms, "delay of every forwarded message")->check(CLI::Range(0, 10000));
        app.add_flag("--impair", flags.impair_at_start, "impair from the start (else: SIGUSR1 on, SIGUSR2 off)");
        app.add_option("--seed", flags.seed, "random seed");
      });
}
