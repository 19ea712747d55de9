// SIGINT/SIGTERM as a pollable file descriptor (signalfd). Construct it before any thread is
// started so every thread inherits the blocked mask; the previous mask is restored on
// destruction. Child processes must unblock the signals after fork (see supervisor).
#pragma once

#include <signal.h>

namespace rgnav::runtime {

class SignalWatcher
{
 public:
  SignalWatcher();
  ~SignalWatcher();
  SignalWatcher(const SignalWatcher&) = delete;
  SignalWatcher& operator=(const SignalWatcher&) = delete;

  int fd() const { return fd_; }
  // Reads pending signals; returns the last one received, or 0 if none was pending.
  int take();

 private:
  int fd_ = -1;
  sigset_t previous_{};
};

}  // namespace rgnav::runtime
