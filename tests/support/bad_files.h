// The three bad files every reader of a file must refuse (issue 35): random bytes, an empty
// file, and a valid file cut off in the middle of its content. They are made at test time in a
// temporary folder, never checked in; the random bytes are seeded, so a failure repeats.
#pragma once

#include <chrono>
#include <string>
#include <vector>

#include "child_process.h"

namespace rgnav::testing {

struct BadFile
{
  std::string kind;   // "random", "empty" or "truncated"
  std::string path;
};

// `n` pseudo-random bytes (seeded: the same bytes every run).
std::string random_bytes(size_t n, uint32_t seed = 35);

// Writes <dir>/random_<name>, <dir>/empty_<name> and <dir>/truncated_<name> (the first `keep`
// bytes of `valid`; default: half of them). The name keeps its extension, which some readers
// go by.
std::vector<BadFile> write_bad_files(const std::string& dir, const std::string& name, const std::string& valid,
                                     size_t keep = std::string::npos);

// Writes `bytes` to `path` (binary, truncating).
void write_bytes(const std::string& path, const std::string& bytes);

// A tool run to completion with its output captured.
struct ToolRun
{
  ExitStatus status;
  std::string out, err;
};
// Runs argv with stdout/stderr captured in files under `capture_dir`.
ToolRun run_tool(std::vector<std::string> argv, const std::string& capture_dir,
                 std::chrono::milliseconds timeout = std::chrono::seconds(120));

// True when `path` does not exist or is a folder with no file in it (at any depth).
bool nothing_written(const std::string& path);

}  // namespace rgnav::testing
