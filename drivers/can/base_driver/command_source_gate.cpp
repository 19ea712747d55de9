#include "base_driver/command_source_gate.h"

namespace rgnav::can::base {

namespace {

// A sender's name as it may appear in a log line or heartbeat: printable, at most 48 characters.
std::string printable(const std::string& s)
{
  if (s.empty()) return "(no source)";
  std::string out;
  for (char c : s) {
    if (out.size() >= 48) return out + "...";
    out += (c >= 0x20 && c < 0x7f) ? c : '?';
  }
  return out;
}

}  // namespace

bool CommandSourceGate::locked_out(Clock::time_point now) const
{
  return last_foreign_ && now - *last_foreign_ < options_.foreign_quiet;
}

CommandDecision CommandSourceGate::on_command(const std::string& source, double v, double omega,
                                              Clock::duration deadline, Clock::time_point now)
{
  const bool from_hold = !options_.hold_source.empty() && source == options_.hold_source;
  const bool zero = v == 0.0 && omega == 0.0;
  if (from_hold && zero) {
    // The safety net wins over the owner for as long as its command is valid.
    if (now + deadline > hold_until_) hold_until_ = now + deadline;
    return {CommandVerdict::kStop, ""};
  }
  if (source == options_.owner) {
    if (locked_out(now)) return {CommandVerdict::kQuickStop, ""};
    if (now < hold_until_) return {CommandVerdict::kStop, ""};
    return {CommandVerdict::kFollow, ""};
  }
  // A second source (or the hold asking for motion, which it never does).
  ++refused_;
  const bool news = !locked_out(now) || printable(source) != foreign_;
  last_foreign_ = now;
  foreign_ = printable(source);
  if (!news) return {CommandVerdict::kQuickStop, ""};
  alert_ = "BASE_CMD from '" + printable(source) + "' refused: the channel belongs to '" + printable(options_.owner) + "'" +
           (from_hold ? " ('" + printable(source) + "' may only command zero)" : std::string()) +
           "; drives quick-stopped until '" + printable(source) + "' is silent for " +
           std::to_string(options_.foreign_quiet.count()) + " ms";
  return {CommandVerdict::kQuickStop, alert_};
}

}  // namespace rgnav::can::base
