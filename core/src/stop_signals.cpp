// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/stop_signals.h"

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <mutex>
#include <thread>

#include "tinlod/output_files.h"

namespace tinlod {
namespace {

constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP};
constexpr auto kGrace = std::chrono::milliseconds(1000);

volatile std::sig_atomic_t gSignals = 0;   // how many stop signals arrived while caught
std::atomic<bool> gCaught{false};
struct sigaction gPrevious[3];

void onSignal(int signal) {
  if (gSignals >= 2) {  // a third: the watchdog is stuck somehow; end the way the user asks
    std::signal(signal, SIG_DFL);
    std::raise(signal);
  }
  gSignals = gSignals + 1;
}

void say(const char* text) {
  const ssize_t ignored = write(STDERR_FILENO, text, std::char_traits<char>::length(text));
  (void)ignored;
}

// Runs beside the work for the life of the process: it alone may end the process early,
// from an ordinary thread where removing files is safe (a signal handler could not).
void watch() {
  for (;;) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    if (!gSignals || !gCaught) continue;
    const auto asked = std::chrono::steady_clock::now();
    while (gSignals < 2 && gCaught && std::chrono::steady_clock::now() - asked < kGrace)
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    if (!gCaught) {  // the host took its handlers back: the stop was answered
      gSignals = 0;
      continue;
    }
    if (abandonStagedOutputs())
      say("\nERROR: stopped at the end: the outputs were already in place\n");
    else
      say("\nERROR: stopped before the end; nothing was written\n");
    _exit(130);
  }
}

}  // namespace

void catchStopSignals() {
  static std::once_flag started;
  std::call_once(started, [] { std::thread(watch).detach(); });
  if (gCaught.exchange(true)) return;
  gSignals = 0;
  struct sigaction action {};
  action.sa_handler = onSignal;
  sigemptyset(&action.sa_mask);
  for (int i = 0; i < 3; ++i) {
    sigaction(kSignals[i], nullptr, &gPrevious[i]);
    // nohup's SIGHUP stays ignored: the run must outlive its terminal. (SIGINT is caught even
    // where a shell ignores it for a job it puts in the background: scripts stop those by it.)
    if (kSignals[i] != SIGHUP || gPrevious[i].sa_handler != SIG_IGN) sigaction(kSignals[i], &action, nullptr);
  }
}

void releaseStopSignals() {
  if (!gCaught.exchange(false)) return;
  for (int i = 0; i < 3; ++i) sigaction(kSignals[i], &gPrevious[i], nullptr);
  gSignals = 0;
}

bool stopRequested() { return gSignals > 0; }

}  // namespace tinlod
