// One owner for the drive commands. BASE_CMD is an open channel: any process on the robot's
// network can publish on it, and two senders would fight silently (the drives follow whichever
// spoke last). The gate knows the channel's owner from the config, not from who spoke first
// (an intruder that spoke first, or a second lld after a bad restart, would otherwise own the
// robot), plus the one second source that is allowed: the supervisor's hold, the safety net,
// which only ever commands zero and then always wins (for that command's deadline). Any other
// source — or the hold source commanding motion — is refused the moment it is heard, the
// drives are quick-stopped (a safety event: nobody knows who drives the robot) and held so,
// and an alert names both sources; the owner is followed again once the foreign source has
// been silent for `foreign_quiet`. No LCM, no clock of its own.
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

namespace rgnav::can::base {

struct CommandSourceOptions
{
  std::string owner = "lld";               // base.command_source
  std::string hold_source = "supervisor";  // base.hold_source ("" none): zero commands only
  std::chrono::milliseconds foreign_quiet{1000};  // base.foreign_quiet_ms
};

enum class CommandVerdict
{
  kFollow,     // pass the command to the drives
  kStop,       // command zero instead: a controlled stop (the hold)
  kQuickStop,  // the channel has a second source: quick stop, held while locked_out()
};

struct CommandDecision
{
  CommandVerdict verdict = CommandVerdict::kStop;
  std::string alert;  // set when a (new) foreign source is heard: raise it
};

class CommandSourceGate
{
 public:
  using Clock = std::chrono::steady_clock;

  explicit CommandSourceGate(CommandSourceOptions options) : options_(std::move(options)) {}

  // A command from `source`, received at `now`, void after `deadline`.
  CommandDecision on_command(const std::string& source, double v, double omega, Clock::duration deadline,
                             Clock::time_point now);
  // A foreign source was heard less than foreign_quiet ago: the drives are held in quick stop.
  bool locked_out(Clock::time_point now) const;
  // The alert of the current (or last) lockout, "" if there never was one.
  const std::string& alert() const { return alert_; }
  const std::string& foreign_source() const { return foreign_; }  // printable
  int64_t refused() const { return refused_; }
  const CommandSourceOptions& options() const { return options_; }

 private:
  const CommandSourceOptions options_;
  std::optional<Clock::time_point> last_foreign_;
  Clock::time_point hold_until_{};
  std::string foreign_;
  std::string alert_;
  int64_t refused_ = 0;
};

}  // namespace rgnav::can::base
