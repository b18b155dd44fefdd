#pragma once
// SIGINT, SIGTERM, SIGQUIT and SIGHUP (unless ignored when rtrt starts) stop rtrt at once, at
// any point of its work: the signal goes on to the child processes running, the registered
// temporaries are removed, a line says so, and the process exits 128 + the signal's number (130,
// 143, 129, 131). Outputs take their name only when complete
// (OutputFile), so what was finished stays whole.
#include <mutex>
#include <string>

namespace rtrt {

// Blocks those signals and waits for them on a thread of their own, which does the cleanup
// with ordinary (not async-signal-safe) calls; a handler hands the signals on from threads that
// were started before. Call once, first thing in main: rtrt's own threads inherit the mask.
void InstallInterruptHandler();

// The temporaries an interrupt removes (files, or folders with what they hold). While a lock is
// alive the interrupt waits for it, so a temporary made and registered, or renamed (removed) and
// unregistered, under one lock is never half done when the cleanup runs.
class TemporariesLock {
  public:
    TemporariesLock();
    TemporariesLock(const TemporariesLock&) = delete;
    TemporariesLock& operator=(const TemporariesLock&) = delete;

    void Register(const std::string& path);
    void Unregister(const std::string& path);
    // Child processes running: an interrupt hands its signal on to each and waits for them
    // (SIGKILL after a few seconds) before it removes the temporaries, so that a child neither
    // goes on working nor writes a file after the cleanup.
    void RegisterChild(int pid);
    void UnregisterChild(int pid);

  private:
    std::unique_lock<std::mutex> lock_;
};

}  // namespace rtrt
