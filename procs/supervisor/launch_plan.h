// Validation of a parsed launch config and what the supervisor needs to run it: each
// command's argv (exec line split and ${VAR}-expanded like a shell would, without running
// anything), its executable resolved, and a start order that respects `depends`.
// All problems are collected and reported together, one per line, each with file:line.
#pragma once

#include <string>
#include <vector>

#include "launch_config.h"
#include "launch_parser.h"

namespace rgnav::supervisor {

struct PlanOptions
{
  std::string root;       // repo root: relative `config =` paths and executables resolve here
  std::string bin_dir;    // searched first for bare executable names (the build's bin/)
  // Missing executables are an error unless allowed; allowed ones are listed in `missing`
  // (the fault harness reports them as pending, `launch --skip-missing` leaves them stopped).
  bool allow_missing_executables = false;
};

struct PlannedCommand
{
  CommandSpec spec;
  std::string executable;          // resolved path ("" if missing)
  std::vector<std::string> argv;   // argv[0] as written
};

struct LaunchPlan
{
  LaunchConfig config;
  std::vector<PlannedCommand> commands;  // in start order (dependencies first)
  std::vector<std::string> missing;      // commands whose executable was not found

  const PlannedCommand* find(const std::string& name) const;
};

// Throws LaunchError listing every problem found.
LaunchPlan make_plan(const LaunchConfig& config, const PlanOptions& options);

// Splits and expands an exec line (quotes, backslashes, $VAR, ${VAR}); no command
// substitution. Throws LaunchError (with `where`) on undefined variables or bad syntax.
std::vector<std::string> split_exec(const std::string& exec, const SourceLocation& where);

}  // namespace rgnav::supervisor
