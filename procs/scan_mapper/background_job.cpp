#include "scan_mapper/background_job.h"

#include <sys/eventfd.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace rgnav::scan_mapper {

BackgroundJob::BackgroundJob() : fd_(::eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC))
{
  if (fd_ < 0) throw std::runtime_error(std::string("eventfd: ") + std::strerror(errno));
}

BackgroundJob::~BackgroundJob()
{
  if (thread_.joinable()) thread_.join();
  ::close(fd_);
}

void BackgroundJob::start(std::function<void()> work)
{
  if (thread_.joinable()) throw std::logic_error("BackgroundJob::start while a job is out");
  error_.clear();
  thread_ = std::thread([this, work = std::move(work)] {
    try {
      work();
    } catch (const std::exception& e) {
      error_ = e.what();  // read by the node thread only after the eventfd said done
    } catch (...) {
      error_ = "unknown exception";
    }
    const uint64_t one = 1;
    while (::write(fd_, &one, sizeof one) < 0 && errno == EINTR) {
    }
  });
}

void BackgroundJob::wait()
{
  if (!thread_.joinable()) return;
  thread_.join();
  uint64_t n = 0;
  [[maybe_unused]] const ssize_t r = ::read(fd_, &n, sizeof n);  // nonblocking; done was signalled
}

bool BackgroundJob::finished()
{
  uint64_t n = 0;
  if (::read(fd_, &n, sizeof n) != static_cast<ssize_t>(sizeof n)) return false;
  if (thread_.joinable()) thread_.join();
  return true;
}

}  // namespace rgnav::scan_mapper
