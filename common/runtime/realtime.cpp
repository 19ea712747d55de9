#include "runtime/realtime.h"

#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>

#include <spdlog/spdlog.h>

#include <cerrno>
#include <cstring>

namespace rgnav::runtime {

std::string request_realtime(int priority, bool lock_memory, bool* granted)
{
  std::string what;
  bool ok = true;
  if (lock_memory && mlockall(MCL_CURRENT | MCL_FUTURE) != 0) {
    ok = false;
    what += std::string("mlockall refused (") + std::strerror(errno) + ")";
  } else if (lock_memory) {
    what += "memory locked";
  }
  if (priority > 0) {
    sched_param sp{};
    sp.sched_priority = priority;
    const int rc = pthread_setschedparam(pthread_self(), SCHED_FIFO, &sp);
    if (rc != 0) {
      ok = false;
      what += std::string(what.empty() ? "" : ", ") + "SCHED_FIFO " + std::to_string(priority) + " refused (" +
              std::strerror(rc) + "): running with normal scheduling";
    } else {
      what += std::string(what.empty() ? "" : ", ") + "SCHED_FIFO priority " + std::to_string(priority);
    }
  }
  if (granted) *granted = ok;
  return what;
}

bool request_realtime_logged(std::string_view thread, int priority, bool lock_memory, std::string_view if_refused)
{
  bool granted = false;
  const std::string what = request_realtime(priority, lock_memory, &granted);
  if (granted)
    spdlog::info("{}: {}", thread, what);
  else if (if_refused.empty())
    spdlog::warn("{}: {}", thread, what);
  else
    spdlog::warn("{}: {} ({})", thread, what, if_refused);
  return granted;
}

}  // namespace rgnav::runtime
