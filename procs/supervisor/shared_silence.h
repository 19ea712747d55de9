// Heartbeats that stop for several processes at once are a stall of the host (the processes
// starved while the supervisor ran on) or of the bus (a flood, a late receive queue), not that
// many hangs. The supervisor's own tick lateness catches the stalls it shared (on_host_stall);
// this catches those it did not feel. Pure bookkeeping on a steady clock: no processes here.
//
// The rule, for a process whose heartbeats have been silent past its bound:
//  - another watched process's newest heartbeat lies within the window of its own: their
//    silences began together, and its verdict is held, at most `stall_hold` longer;
//  - heard again within the hold: it was the stall, not the process. The first of them heard
//    ends the shared silence; it is counted as a stall of the host, as long as all of them
//    were silent together (from the newest of their last heartbeats to that first one back);
//  - still silent at its bound + stall_hold: hung (one that stays silent while the others come
//    back is, and so is each of several stopped at once: the hold is bounded);
//  - silent alone: hung at its bound, as before.
// Why the window is safe: at the moment a silence reaches its bound, a healthy process's newest
// heartbeat is at most one heartbeat period old, so it lies outside the window when the window
// is at most bound - period. A bound shorter than two periods would call a process hung for one
// lost heartbeat, so bound / 2 is the widest window any sane bound allows (silence_window).
// Processes starved together stopped beating within one period of each other (each beats on
// its own phase): the window must be wider than a period to see them all (5 Hz: 200 ms).
#pragma once

#include <chrono>
#include <optional>
#include <string>
#include <vector>

namespace rgnav::supervisor {

// The window for a process whose heartbeat bound is `bound`: the configured one, at most
// half the bound.
std::chrono::steady_clock::duration silence_window(std::chrono::milliseconds configured, std::chrono::milliseconds bound);

// Two silences began together: their newest heartbeats lie within `window` of each other.
bool began_together(std::chrono::steady_clock::time_point a, std::chrono::steady_clock::time_point b,
                    std::chrono::steady_clock::duration window);

// One shared silence: from the first of its processes held to the last one released.
class SharedSilence
{
 public:
  using Clock = std::chrono::steady_clock;

  // `name` is held; `newest_beat` is the newest last heartbeat among it and the processes silent
  // with it (the silence they share began after that).
  void hold(const std::string& name, Clock::time_point newest_beat);
  // A held process heard again at `now`. For the first one back, the length of the silence
  // they all shared (then counted as a stall); after that nullopt.
  std::optional<Clock::duration> heard(Clock::time_point now);
  // A held process judged hung, stopped or gone without being heard again.
  void release();
  // The supervisor stalled for `gap` (on_host_stall): the silence is that much shorter.
  void shift(Clock::duration gap, Clock::time_point now);

  bool open() const { return held_ > 0; }
  // The processes held in this silence so far, "a, b" (for the log).
  std::string names() const;

 private:
  int held_ = 0;
  bool counted_ = false;
  Clock::time_point newest_beat_{};
  std::vector<std::string> names_;
};

}  // namespace rgnav::supervisor
