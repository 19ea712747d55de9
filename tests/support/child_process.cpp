#include "child_process.h"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <thread>

extern char** environ;

namespace rgnav::testing {

std::string ExitStatus::describe() const
{
  if (exited) return "exit " + std::to_string(code);
  if (signaled) return std::string("signal ") + std::to_string(signal) + " (" + strsignal(signal) + ")";
  return "not finished";
}

namespace {

ExitStatus from_wait_status(int ws)
{
  ExitStatus s;
  if (WIFEXITED(ws)) {
    s.exited = true;
    s.code = WEXITSTATUS(ws);
  } else if (WIFSIGNALED(ws)) {
    s.signaled = true;
    s.signal = WTERMSIG(ws);
  }
  return s;
}

std::vector<std::string> merged_environment(const std::vector<std::string>& extra)
{
  std::map<std::string, std::string> env;
  std::vector<std::string> order;
  auto put = [&](const std::string& kv) {
    const auto eq = kv.find('=');
    const std::string key = kv.substr(0, eq);
    if (!env.count(key)) order.push_back(key);
    env[key] = kv;
  };
  for (char** e = environ; *e; ++e) put(*e);
  for (const auto& kv : extra) put(kv);
  std::vector<std::string> out;
  for (const auto& k : order) out.push_back(env[k]);
  return out;
}

class SpawnSetup
{
 public:
  SpawnSetup()
  {
    posix_spawnattr_init(&attr_);
    posix_spawn_file_actions_init(&actions_);
  }
  ~SpawnSetup()
  {
    posix_spawnattr_destroy(&attr_);
    posix_spawn_file_actions_destroy(&actions_);
  }
  SpawnSetup(const SpawnSetup&) = delete;
  SpawnSetup& operator=(const SpawnSetup&) = delete;
  posix_spawnattr_t attr_;
  posix_spawn_file_actions_t actions_;
};

}  // namespace

ChildProcess::ChildProcess(std::vector<std::string> argv, ChildOptions options)
    : argv_(std::move(argv)), options_(std::move(options))
{
  if (argv_.empty()) throw std::invalid_argument("ChildProcess: empty argv");
  SpawnSetup setup;
  sigset_t none;
  sigemptyset(&none);
  sigset_t defaults;
  sigemptyset(&defaults);
  for (int sig : {SIGINT, SIGTERM, SIGPIPE, SIGHUP, SIGQUIT}) sigaddset(&defaults, sig);
  posix_spawnattr_setsigmask(&setup.attr_, &none);
  posix_spawnattr_setsigdefault(&setup.attr_, &defaults);
  posix_spawnattr_setpgroup(&setup.attr_, 0);
  posix_spawnattr_setflags(&setup.attr_, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF | POSIX_SPAWN_SETPGROUP);
  if (!options_.stdout_path.empty())
    posix_spawn_file_actions_addopen(&setup.actions_, STDOUT_FILENO, options_.stdout_path.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (!options_.stderr_path.empty())
    posix_spawn_file_actions_addopen(&setup.actions_, STDERR_FILENO, options_.stderr_path.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (!options_.working_dir.empty())
    posix_spawn_file_actions_addchdir_np(&setup.actions_, options_.working_dir.c_str());

  std::vector<char*> args;
  for (auto& a : argv_) args.push_back(a.data());
  args.push_back(nullptr);
  std::vector<std::string> env = merged_environment(options_.env);
  std::vector<char*> envp;
  for (auto& e : env) envp.push_back(e.data());
  envp.push_back(nullptr);

  const int rc = posix_spawnp(&pid_, args[0], &setup.actions_, &setup.attr_, args.data(), envp.data());
  if (rc != 0) {
    pid_ = -1;
    throw std::runtime_error("cannot start '" + argv_[0] + "': " + std::strerror(rc));
  }
}

ChildProcess::~ChildProcess() { kill_and_reap(); }

ChildProcess::ChildProcess(ChildProcess&& other) noexcept
    : argv_(std::move(other.argv_)), options_(std::move(other.options_)), pid_(other.pid_),
      status_(std::move(other.status_))
{
  other.pid_ = -1;
}

ChildProcess& ChildProcess::operator=(ChildProcess&& other) noexcept
{
  if (this != &other) {
    kill_and_reap();
    argv_ = std::move(other.argv_);
    options_ = std::move(other.options_);
    pid_ = other.pid_;
    status_ = std::move(other.status_);
    other.pid_ = -1;
  }
  return *this;
}

bool ChildProcess::try_reap()
{
  if (pid_ < 0 || status_) return status_.has_value();
  int ws = 0;
  const pid_t r = waitpid(pid_, &ws, WNOHANG);
  if (r == pid_) {
    status_ = from_wait_status(ws);
    return true;
  }
  return false;
}

bool ChildProcess::running() { return pid_ > 0 && !try_reap(); }

bool ChildProcess::signal(int sig) { return running() && ::kill(pid_, sig) == 0; }

bool ChildProcess::signal_group(int sig) { return running() && ::kill(-pid_, sig) == 0; }

std::optional<ExitStatus> ChildProcess::wait_for(std::chrono::milliseconds timeout)
{
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  for (;;) {
    if (pid_ < 0) return status_;
    if (try_reap()) return status_;
    if (std::chrono::steady_clock::now() >= deadline) return std::nullopt;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
}

ExitStatus ChildProcess::stop(std::chrono::milliseconds grace)
{
  if (signal(SIGTERM)) {
    if (auto s = wait_for(grace)) return *s;
  }
  kill_and_reap();
  return status_.value_or(ExitStatus{});
}

void ChildProcess::kill_and_reap()
{
  if (pid_ < 0) return;
  if (!status_) {
    // The group too: a child may have forked helpers (e.g. a shell script's children). Only
    // while the leader is unreaped: after that its pid (= the group id) may be reused.
    ::kill(-pid_, SIGKILL);
    ::kill(pid_, SIGKILL);
    int ws = 0;
    while (waitpid(pid_, &ws, 0) < 0 && errno == EINTR) {
    }
    status_ = from_wait_status(ws);
  }
}

std::string ChildProcess::stderr_text() const
{
  return options_.stderr_path.empty() ? std::string() : read_file(options_.stderr_path);
}

ChildProcess& ProcessGroup::start(std::vector<std::string> argv, ChildOptions options)
{
  children_.emplace_back(std::move(argv), std::move(options));
  return children_.back();
}

void ProcessGroup::stop_all(std::chrono::milliseconds grace)
{
  for (auto it = children_.rbegin(); it != children_.rend(); ++it) it->signal(SIGTERM);
  const auto deadline = std::chrono::steady_clock::now() + grace;
  for (auto it = children_.rbegin(); it != children_.rend(); ++it) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    it->wait_for(std::max(left, std::chrono::milliseconds(0)));
  }
  children_.clear();  // kills and reaps whatever did not stop
}

ExitStatus run_to_completion(std::vector<std::string> argv, std::chrono::milliseconds timeout, ChildOptions options)
{
  ChildProcess child(std::move(argv), std::move(options));
  if (auto s = child.wait_for(timeout)) return *s;
  return child.stop(std::chrono::milliseconds(1000));
}

void expect_clean_stop(ChildProcess& child, std::chrono::milliseconds grace)
{
  const ExitStatus s = child.stop(grace);
  EXPECT_TRUE(s.clean()) << child.name() << ": " << s.describe() << "\n" << child.stderr_text();
}

std::string executable_dir()
{
  char buf[4096];
  const ssize_t n = ::readlink("/proc/self/exe", buf, sizeof buf - 1);
  if (n <= 0) return ".";
  std::string p(buf, static_cast<size_t>(n));
  return p.substr(0, p.rfind('/'));
}

std::string read_file(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TempDir::TempDir(const std::string& prefix)
{
  const char* base = std::getenv("TMPDIR");
  std::string templ = std::string(base && *base ? base : "/tmp") + "/" + prefix + "_XXXXXX";
  if (!mkdtemp(templ.data())) throw std::runtime_error("mkdtemp failed: " + std::string(std::strerror(errno)));
  path_ = templ;
}

TempDir::~TempDir()
{
  // RGNAV_KEEP_TEST_DIRS=1 keeps logs and outputs for a post-mortem.
  if (const char* keep = std::getenv("RGNAV_KEEP_TEST_DIRS"); keep && *keep == '1') return;
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

}  // namespace rgnav::testing
