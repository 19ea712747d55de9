// The model of a procman-style launch configuration: commands (processes) in nested groups,
// and scripts. The syntax is libbot2 procman's sheriff config, so operators' existing files
// load; rgnav adds attributes it needs (dependencies, environment, config file, heartbeat
// watching). Every element remembers where in the file it was written, so validation errors
// can say file:line.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace rgnav::supervisor {

struct SourceLocation
{
  std::string file;
  int line = 0;
  std::string str() const { return file + ":" + std::to_string(line); }
};

struct CommandSpec
{
  std::string name;              // procman's nickname; unique in the whole config
  std::string group;             // group path "drivers/laser", "" at top level
  std::string exec;              // command line, shell-like words with ${VAR} expansion
  std::string host;              // deputy that runs it ("" = every deputy)
  bool auto_respawn = true;      // rgnav restarts by default; "false" opts out (procman: off)
  bool auto_respawn_set = false;  // written in the file (else the supervisor default applies)
  int stop_signal = 2;           // procman default: SIGINT
  double stop_time_allowed_s = 7.0;  // grace period before SIGKILL (procman default 7 s)
  // rgnav extensions
  std::vector<std::string> depends;  // commands that must be running before this one starts
  std::vector<std::pair<std::string, std::string>> env;  // added to the environment
  std::string config;            // process config file, passed as --config (relative: repo root)
  bool heartbeat = true;         // watched by HEARTBEAT; false for tools (lcm-logger)
  int heartbeat_timeout_ms = 0;  // 0 = the supervisor default
  int startup_timeout_ms = 0;    // time to the first heartbeat; 0 = the supervisor default
  // Longest time the heartbeat's progress counter may stand still while heartbeats go on
  // (long work without progress = hung); 0 = the supervisor default.
  int work_timeout_ms = 0;
  std::vector<std::string> inputs;  // input channels (fault injection, documentation)
  bool safety_critical = false;  // failing it stops and holds the robot
  // A job rather than a service (a tour, a planning step): exit 0 means done, not a failure;
  // it is not restarted, and commands that depend on it may start once it is done.
  bool oneshot = false;
  SourceLocation where;          // the `cmd` keyword
  SourceLocation exec_where;     // the exec attribute (missing-executable errors point here)
};

struct ScriptAction
{
  enum class Kind { kStart, kStop, kRestart, kWaitMs, kWaitStatus, kRunScript };
  enum class Target { kEverything, kCommand, kGroup };
  Kind kind = Kind::kWaitMs;
  Target target = Target::kEverything;
  std::string ident;        // command, group or script name
  std::string wait_status;  // "", "running" or "stopped"
  int delay_ms = 0;
  SourceLocation where;
};

struct ScriptSpec
{
  std::string name;
  std::vector<ScriptAction> actions;
  SourceLocation where;
};

struct GroupSpec
{
  std::string path;  // "drivers" or "perception/vision"
  SourceLocation where;
};

struct LaunchConfig
{
  std::string file;
  std::vector<CommandSpec> commands;  // in file order
  std::vector<GroupSpec> groups;
  std::vector<ScriptSpec> scripts;

  const CommandSpec* find(const std::string& name) const;
  bool has_group(const std::string& path_or_name) const;
  // Commands whose group path is `group` or lies below it; a single path component also
  // matches a group of that name at any depth.
  std::vector<const CommandSpec*> in_group(const std::string& group) const;
};

}  // namespace rgnav::supervisor
