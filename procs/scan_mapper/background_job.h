// One job at a time on a worker thread, with a descriptor that becomes readable when it is
// done, so a single-threaded node can wait for it in its poll loop (runtime::Node::watch_fd)
// and take the result on its own thread. The job must touch nothing the node thread uses.
#pragma once

#include <functional>
#include <string>
#include <thread>

namespace rgnav::scan_mapper {

class BackgroundJob
{
 public:
  BackgroundJob();
  ~BackgroundJob();  // waits for a running job
  BackgroundJob(const BackgroundJob&) = delete;
  BackgroundJob& operator=(const BackgroundJob&) = delete;

  // Starts work on the worker thread; throws std::logic_error if a job is running or unfetched.
  void start(std::function<void()> work);
  bool busy() const { return thread_.joinable(); }
  // Blocks until a running job is done and consumes its notification (finished() is then
  // false): for shutting down.
  void wait();
  // Readable once the job is done (eventfd).
  int fd() const { return fd_; }
  // True once, when the job has finished (joins it); error() then holds what it threw ("" =
  // nothing). Does not block.
  bool finished();
  const std::string& error() const { return error_; }

 private:
  int fd_ = -1;
  std::thread thread_;
  std::string error_;
};

}  // namespace rgnav::scan_mapper
