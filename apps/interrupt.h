// Lucerna CLI: SIGINT, SIGTERM and SIGHUP. While nothing worth saving exists (the scene is being
// read, the acceleration structure built, the first pass rendered) a signal ends the process at
// once with exit code 3 and a message naming the stage; no file is touched. Afterwards it only
// asks the render to stop at the pass in flight (the caller writes what it has and exits 3).
#pragma once

#include <atomic>

namespace lu::app {

// Installs the handlers (idempotent). The stage starts as "starting; nothing written".
void InstallSignalHandlers();
// What the process is doing and what an exit now leaves behind, the end of the message of an
// immediate exit ("interrupted by SIGINT while " + stage). `stage` must have static storage (a
// string literal). nullptr: a signal only sets the cancel flag and is remembered (CaughtSignal).
void SetExitStage(const char *stage);
// Set by a signal once the exit stage is nullptr.
const std::atomic<bool> *CancelFlag();
// The last signal caught (0: none).
int CaughtSignal();
// "SIGINT", "SIGTERM", "SIGHUP"; "a signal" for any other.
const char *SignalName(int sig);

}  // namespace lu::app
