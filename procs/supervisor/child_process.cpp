#include "child_process.h"

#include <fcntl.h>
#include <sched.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include "proc_info.h"

namespace rgnav::supervisor {

namespace {

void write_holder(int fd, pid_t pid, uint64_t start_ticks)
{
  const std::string text = std::to_string(pid) + " " + std::to_string(start_ticks) + "\n";
  if (ftruncate(fd, 0) == 0) {
    [[maybe_unused]] const ssize_t n = pwrite(fd, text.data(), text.size(), 0);
  }
}

std::optional<std::pair<pid_t, uint64_t>> read_holder(int fd)
{
  char buf[64] = {0};
  const ssize_t n = pread(fd, buf, sizeof buf - 1, 0);
  if (n <= 0) return std::nullopt;
  long long pid = 0;
  unsigned long long ticks = 0;
  if (std::sscanf(buf, "%lld %llu", &pid, &ticks) != 2) return std::nullopt;
  return std::make_pair(static_cast<pid_t>(pid), static_cast<uint64_t>(ticks));
}

}  // namespace

void make_dirs(const std::string& path)
{
  std::string partial;
  for (size_t i = 0; i <= path.size(); ++i) {
    if (i == path.size() || (path[i] == '/' && i > 0)) {
      partial = path.substr(0, i);
      if (mkdir(partial.c_str(), 0755) != 0 && errno != EEXIST)
        throw std::runtime_error("cannot create " + partial + ": " + std::strerror(errno));
    }
  }
}

std::optional<std::pair<pid_t, uint64_t>> lock_holder(const std::string& lock_path)
{
  const int fd = open(lock_path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return std::nullopt;
  std::optional<std::pair<pid_t, uint64_t>> holder;
  if (flock(fd, LOCK_SH | LOCK_NB) != 0 && errno == EWOULDBLOCK) holder = read_holder(fd);
  close(fd);
  return holder;
}

SpawnResult spawn_child(const SpawnRequest& request)
{
  SpawnResult result;
  int lock_fd = -1;
  if (!request.lock_path.empty()) {
    lock_fd = open(request.lock_path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (lock_fd < 0) {
      result.error = "cannot open lock " + request.lock_path + ": " + std::strerror(errno);
      return result;
    }
    if (flock(lock_fd, LOCK_EX | LOCK_NB) != 0) {
      const auto holder = read_holder(lock_fd);
      close(lock_fd);
      result.error = "another instance holds " + request.lock_path;
      if (holder) {
        result.lock_holder = holder->first;
        result.lock_holder_start_ticks = holder->second;
        result.error += " (pid " + std::to_string(holder->first) + ")";
      }
      return result;
    }
  }

  // Everything the child needs is prepared before fork: after it, only async-signal-safe calls.
  std::vector<char*> argv;
  for (const auto& a : request.argv) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  std::vector<std::string> env_strings;
  for (char** e = environ; *e; ++e) {
    bool overridden = false;
    for (const auto& [k, v] : request.env)
      overridden = overridden || (std::strncmp(*e, k.c_str(), k.size()) == 0 && (*e)[k.size()] == '=');
    if (!overridden) env_strings.emplace_back(*e);
  }
  for (const auto& [k, v] : request.env) env_strings.push_back(k + "=" + v);
  std::vector<char*> envp;
  for (auto& s : env_strings) envp.push_back(s.data());
  envp.push_back(nullptr);

  // exec errors come back through a close-on-exec pipe: EOF means exec succeeded.
  int errpipe[2];
  if (pipe2(errpipe, O_CLOEXEC) != 0) {
    if (lock_fd >= 0) close(lock_fd);
    result.error = std::string("pipe: ") + std::strerror(errno);
    return result;
  }

  const pid_t pid = fork();
  if (pid < 0) {
    result.error = std::string("fork: ") + std::strerror(errno);
    close(errpipe[0]);
    close(errpipe[1]);
    if (lock_fd >= 0) close(lock_fd);
    return result;
  }
  if (pid == 0) {
    // Child. Own session: survives the supervisor, signalled as a group.
    setsid();
    // The rgnav runtime blocks SIGINT/SIGTERM (signalfd); a blocked mask survives exec.
    sigset_t none;
    sigemptyset(&none);
    sigprocmask(SIG_SETMASK, &none, nullptr);
    for (int s = 1; s < NSIG; ++s) signal(s, SIG_DFL);
    // Normal scheduling, whatever the supervisor's thread runs at (node.realtime_priority): a
    // process asks for its own real-time threads.
    const sched_param normal{};
    sched_setscheduler(0, SCHED_OTHER, &normal);
    if (lock_fd >= 0) {
      const int flags = fcntl(lock_fd, F_GETFD);
      fcntl(lock_fd, F_SETFD, flags & ~FD_CLOEXEC);  // the child keeps the lock after exec
    }
    execve(request.executable.c_str(), argv.data(), envp.data());
    const int err = errno;
    [[maybe_unused]] const ssize_t n = write(errpipe[1], &err, sizeof err);
    _exit(127);
  }
  close(errpipe[1]);
  int child_errno = 0;
  ssize_t n;
  do {
    n = read(errpipe[0], &child_errno, sizeof child_errno);
  } while (n < 0 && errno == EINTR);
  close(errpipe[0]);
  if (n == static_cast<ssize_t>(sizeof child_errno)) {
    int status = 0;
    waitpid(pid, &status, 0);
    if (lock_fd >= 0) close(lock_fd);
    result.error = "exec " + request.executable + ": " + std::strerror(child_errno);
    return result;
  }
  result.pid = pid;
  if (const auto st = read_proc_stat(pid)) result.start_ticks = st->start_ticks;
  if (lock_fd >= 0) {
    write_holder(lock_fd, pid, result.start_ticks);
    close(lock_fd);  // the child's copy holds the lock
  }
  return result;
}

bool signal_child(pid_t pid, int sig)
{
  if (pid <= 0) return false;
  if (kill(-pid, sig) == 0) return true;
  return kill(pid, sig) == 0;
}

std::string describe_wait_status(int status)
{
  if (WIFEXITED(status)) return "exit " + std::to_string(WEXITSTATUS(status));
  if (WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    const char* name = strsignal(sig);
    return "signal " + std::to_string(sig) + (name ? std::string(" (") + name + ")" : "") + (WCOREDUMP(status) ? ", core dumped" : "");
  }
  return "status " + std::to_string(status);
}

SelfLock::SelfLock(const std::string& path)
{
  fd_ = open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw std::runtime_error("cannot open " + path + ": " + std::strerror(errno));
  if (flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const auto holder = read_holder(fd_);
    close(fd_);
    fd_ = -1;
    throw std::runtime_error("another supervisor holds " + path +
                             (holder ? " (pid " + std::to_string(holder->first) + ")" : std::string()));
  }
  const pid_t self = getpid();
  const auto st = read_proc_stat(self);
  write_holder(fd_, self, st ? st->start_ticks : 0);
}

SelfLock::~SelfLock()
{
  if (fd_ >= 0) close(fd_);
}

}  // namespace rgnav::supervisor
