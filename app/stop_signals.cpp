#include "app/stop_signals.hpp"

#include <pthread.h>
#include <unistd.h>

#include <csignal>
#include <thread>

#include "app/simulation.hpp"

namespace atssim::app {

void watch_stop_signals() {
  sigset_t stops;
  sigemptyset(&stops);
  sigaddset(&stops, SIGINT);
  sigaddset(&stops, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &stops, nullptr);  // inherited by every thread created from now on
  std::thread([stops] {
    for (;;) {
      int signal = 0;
      if (sigwait(&stops, &signal) != 0) continue;
      if (stop_requested()) {
        static const char message[] = "\natssim: interrupted again: exiting now (the frames flushed so far are kept)\n";
        (void)!::write(STDERR_FILENO, message, sizeof message - 1);
        ::_exit(130);
      }
      request_stop();
    }
  }).detach();
}

}  // namespace atssim::app
