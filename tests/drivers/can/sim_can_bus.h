// A deterministic CAN bus on simulated time for tests: endpoints are state machines (master,
// emulated drives) that send through a Sink; every frame reaches every other connected
// endpoint, in order. Endpoints can be disconnected (a node cut off the bus, still running)
// and frames dropped by a predicate.
#pragma once

#include <linux/can.h>

#include <chrono>
#include <deque>
#include <functional>
#include <vector>

namespace rgnav::can::testing {

class SimCanBus
{
 public:
  using Clock = std::chrono::steady_clock;
  using Receiver = std::function<void(const can_frame&, Clock::time_point)>;

  // Returns the endpoint id.
  int add(Receiver receiver)
  {
    endpoints_.push_back({std::move(receiver), true});
    return static_cast<int>(endpoints_.size()) - 1;
  }
  std::function<void(const can_frame&)> sink(int id)
  {
    return [this, id](const can_frame& f) {
      if (!endpoints_[static_cast<size_t>(id)].connected) return;
      queue_.push_back({id, f});
    };
  }
  void set_connected(int id, bool connected) { endpoints_[static_cast<size_t>(id)].connected = connected; }
  // Frames for which drop(sender, frame) is true vanish.
  void set_drop(std::function<bool(int, const can_frame&)> drop) { drop_ = std::move(drop); }
  // Delivers everything queued, including frames sent while delivering.
  void deliver()
  {
    while (!queue_.empty()) {
      const auto [from, f] = queue_.front();
      queue_.pop_front();
      log_.push_back({from, f});
      if (drop_ && drop_(from, f)) continue;
      for (size_t i = 0; i < endpoints_.size(); ++i) {
        if (static_cast<int>(i) == from || !endpoints_[i].connected) continue;
        endpoints_[i].receiver(f, now_);
      }
    }
  }
  // Injects a frame (e.g. an error frame) to one endpoint.
  void inject(int to, const can_frame& f) { endpoints_[static_cast<size_t>(to)].receiver(f, now_); }

  Clock::time_point now() const { return now_; }
  void advance(std::chrono::microseconds dt) { now_ += dt; }
  const std::vector<std::pair<int, can_frame>>& log() const { return log_; }
  void clear_log() { log_.clear(); }

 private:
  struct Endpoint
  {
    Receiver receiver;
    bool connected;
  };
  std::vector<Endpoint> endpoints_;
  std::deque<std::pair<int, can_frame>> queue_;
  std::vector<std::pair<int, can_frame>> log_;
  std::function<bool(int, const can_frame&)> drop_;
  Clock::time_point now_ = Clock::time_point(std::chrono::seconds(1000));
};

}  // namespace rgnav::can::testing
