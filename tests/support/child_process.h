// Child processes for multi-process tests. RAII: a ChildProcess that is still running when it
// goes out of scope is killed (SIGKILL to its whole process group) and reaped, so a failing
// test never leaves a publisher behind.
//
// The child starts with SIGINT/SIGTERM unblocked and at their default action: the rgnav runtime
// blocks them in the parent (signalfd), and the blocked mask would otherwise be inherited.
// Each child leads its own process group, so signal_group() reaches what it forks.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <optional>
#include <string>
#include <vector>

namespace rgnav::testing {

struct ExitStatus
{
  bool exited = false;    // normal exit, code valid
  int code = -1;
  bool signaled = false;  // killed by a signal, signal valid
  int signal = 0;

  bool clean() const { return exited && code == 0; }
  std::string describe() const;
};

struct ChildOptions
{
  // Files the child's stdout/stderr go to (truncated); "" inherits the parent's.
  std::string stdout_path;
  std::string stderr_path;
  // Extra environment entries "KEY=VALUE" added to (or replacing in) the parent's.
  std::vector<std::string> env;
  std::string working_dir;  // "" = the parent's
};

class ChildProcess
{
 public:
  // Starts argv[0] (searched in PATH if it has no '/'). Throws std::runtime_error if it
  // cannot be started (missing executable, fork failure).
  ChildProcess(std::vector<std::string> argv, ChildOptions options = {});
  ~ChildProcess();
  ChildProcess(ChildProcess&& other) noexcept;
  ChildProcess& operator=(ChildProcess&& other) noexcept;
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  pid_t pid() const { return pid_; }
  const std::string& name() const { return argv_.front(); }
  bool running();  // reaps the child if it has exited
  // Sends sig to the child (signal_group: to its process group). False if already reaped.
  bool signal(int sig);
  bool signal_group(int sig);
  // Waits up to timeout for the child to exit; nullopt if it is still running.
  std::optional<ExitStatus> wait_for(std::chrono::milliseconds timeout);
  // SIGTERM, wait up to grace, then SIGKILL (group) and wait. Returns how it ended.
  ExitStatus stop(std::chrono::milliseconds grace = std::chrono::milliseconds(5000));
  // The exit status once reaped.
  const std::optional<ExitStatus>& status() const { return status_; }
  // Contents of stderr_path (empty if not captured), for failure messages.
  std::string stderr_text() const;

 private:
  bool try_reap();
  void kill_and_reap();

  std::vector<std::string> argv_;
  ChildOptions options_;
  pid_t pid_ = -1;
  std::optional<ExitStatus> status_;
};

// Several children stopped together (in reverse start order) when the group is destroyed.
class ProcessGroup
{
 public:
  ProcessGroup() = default;
  ~ProcessGroup() { stop_all(std::chrono::milliseconds(2000)); }
  ProcessGroup(const ProcessGroup&) = delete;
  ProcessGroup& operator=(const ProcessGroup&) = delete;

  ChildProcess& start(std::vector<std::string> argv, ChildOptions options = {});
  // SIGTERM to all, then waits; whatever is left after `grace` is killed.
  void stop_all(std::chrono::milliseconds grace);
  size_t size() const { return children_.size(); }
  ChildProcess& operator[](size_t i) { return children_[i]; }

 private:
  std::vector<ChildProcess> children_;
};

// Stops the child (SIGTERM; SIGKILL after `grace`) and fails the test unless it exited 0; the
// failure says how it ended and shows its stderr.
void expect_clean_stop(ChildProcess& child, std::chrono::milliseconds grace = std::chrono::milliseconds(5000));

// Runs argv to completion (at most `timeout`, then kills it). Returns its status.
ExitStatus run_to_completion(std::vector<std::string> argv, std::chrono::milliseconds timeout,
                             ChildOptions options = {});

// Reads a whole file ("" if it does not exist).
std::string read_file(const std::string& path);

// The folder of the running executable: build/bin, beside the processes a test starts.
std::string executable_dir();

// A fresh empty directory under $TMPDIR (or /tmp), removed with its contents on destruction.
class TempDir
{
 public:
  explicit TempDir(const std::string& prefix = "rgnav_test");
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::string& path() const { return path_; }
  std::string file(const std::string& name) const { return path_ + "/" + name; }

 private:
  std::string path_;
};

}  // namespace rgnav::testing
