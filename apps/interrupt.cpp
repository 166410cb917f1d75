// Lucerna CLI: the signal handlers of apps/interrupt.h. The handler uses only async-signal-safe
// calls (atomics, write, _exit).
#include "apps/interrupt.h"

#include <unistd.h>

#include <csignal>
#include <cstring>

#include "apps/commands.h"

namespace lu::app {

namespace {

std::atomic<bool> gCancel{false};
std::atomic<int> gSignal{0};
std::atomic<const char *> gStage{"starting; nothing written"};

void WriteStderr(const char *s) {
    size_t n = 0;
    while (s[n]) ++n;   // strlen is not on every async-signal-safe list
    while (n > 0) {
        ssize_t w = ::write(STDERR_FILENO, s, n);
        if (w <= 0) return;
        s += w;
        n -= size_t(w);
    }
}

extern "C" void OnSignal(int sig) {
    const char *stage = gStage.load();
    if (stage) {
        WriteStderr("\nlucerna: interrupted by ");
        WriteStderr(SignalName(sig));
        WriteStderr(" while ");
        WriteStderr(stage);
        WriteStderr("\n");
        _exit(ExitInterrupted);
    }
    gSignal.store(sig);
    gCancel.store(true);
}

}  // namespace

void InstallSignalHandlers() {
    struct sigaction sa;
    std::memset(&sa, 0, sizeof sa);
    sa.sa_handler = OnSignal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART;
    for (int sig : {SIGINT, SIGTERM, SIGHUP}) sigaction(sig, &sa, nullptr);
}

void SetExitStage(const char *stage) { gStage.store(stage); }

const std::atomic<bool> *CancelFlag() { return &gCancel; }

int CaughtSignal() { return gSignal.load(); }

const char *SignalName(int sig) {
    switch (sig) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    case SIGHUP: return "SIGHUP";
    default: return "a signal";
    }
}

}  // namespace lu::app
