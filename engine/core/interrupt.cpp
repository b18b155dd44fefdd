#include "engine/core/interrupt.h"

#include <pthread.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <system_error>
#include <thread>
#include <vector>

namespace rtrt {
namespace {

struct Temporaries {
    std::mutex mutex;
    std::vector<std::string> paths;  // a path twice when two writers share it, once per writer
    std::vector<pid_t> children;     // running, not yet waited for
};

// How long the children of an interrupted rtrt have to stop before they are killed, and how
// long a killed one is waited for (one in uninterruptible sleep, on a hung mount, may never end).
constexpr int kChildStopMilliseconds = 5000;
constexpr int kChildKillMilliseconds = 2000;

// Hands signo on to every registered child and waits until each has ended (reaped here, or by
// the thread that waits for it), killing those still running after kChildStopMilliseconds and
// going on without those that outlive the kill.
// A child that leads its own process group (ChildOptions::ownProcessGroup) gets it as a group.
void SignalChild(pid_t child, int signo) {
    if (::getpgid(child) == child)
        ::kill(-child, signo);
    else
        ::kill(child, signo);
}

void StopChildren(const std::vector<pid_t>& children, int signo) {
    for (const pid_t child : children) SignalChild(child, signo);
    std::vector<pid_t> running = children;
    for (int waited = 0;
         !running.empty() && waited < kChildStopMilliseconds + kChildKillMilliseconds;
         waited += 10) {
        if (waited == kChildStopMilliseconds)
            for (const pid_t child : running) SignalChild(child, SIGKILL);
        std::erase_if(running, [](pid_t child) {
            int status;
            return ::waitpid(child, &status, WNOHANG) != 0;  // ended, or reaped elsewhere
        });
        if (!running.empty()) ::usleep(10000);
    }
}

// Never destroyed: the interrupt thread may clean up while main returns and statics die.
Temporaries& Registry() {
    static Temporaries* registry = new Temporaries;
    return *registry;
}

// Each ends rtrt as an interrupt: a closed terminal (SIGHUP) or Ctrl-\ (SIGQUIT) had left
// half-written temporaries. SIGHUP stays ignored where the starting process ignores it (nohup);
// the others are handled even so, as a shell ignores SIGINT for a script's background job that
// its tests then interrupt.
constexpr int kInterruptSignals[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT};

const char* SignalName(int signo) {
    switch (signo) {
        case SIGINT:
            return "SIGINT";
        case SIGTERM:
            return "SIGTERM";
        case SIGHUP:
            return "SIGHUP";
        case SIGQUIT:
            return "SIGQUIT";
        default:
            return "a signal";
    }
}

sigset_t handledSignals;  // set by InstallInterruptHandler before the waiting thread starts

[[noreturn]] void CleanUpAndExit(int signo) {
    Temporaries& registry = Registry();
    registry.mutex.lock();  // kept: no thread makes or renames a temporary from here on
    // Before the temporaries: a child still running could write one again after its removal.
    // As SIGTERM: a child (ffmpeg with -nostdin) would dump core on SIGQUIT, and SIGHUP is this
    // process's terminal closing, not theirs.
    StopChildren(registry.children, signo == SIGINT ? SIGINT : SIGTERM);
    // Newest first, so that a file inside a registered folder goes before the folder.
    for (auto path = registry.paths.rbegin(); path != registry.paths.rend(); ++path) {
        std::error_code ignored;  // nothing more can be done about a failure on the way out
        std::filesystem::remove_all(*path, ignored);
    }
    // A progress bar on a terminal leaves its line open.
    char line[160];
    const int size = std::snprintf(line, sizeof(line),
                                   "%srtrt: interrupted (%s): finished outputs are kept, "
                                   "unfinished ones removed\n",
                                   isatty(STDERR_FILENO) ? "\n" : "", SignalName(signo));
    // write(2), not stdio: a thread stuck in stdio holds its lock, and the exit must not wait.
    [[maybe_unused]] const ssize_t written = ::write(STDERR_FILENO, line, size_t(size));
    ::_exit(128 + signo);
}

pthread_t interruptThread;  // set before the forwarding handler is installed

// Threads that libraries start before main (log4cplus, loaded with OpenImageIO, starts a pool in
// its static initialiser) do not block the two signals: one delivered to them is handed on.
void ForwardToInterruptThread(int signo) {
    const int savedErrno = errno;
    pthread_kill(interruptThread, signo);
    errno = savedErrno;
}

void WaitForInterrupt() {
    int signo = 0;
    while (sigwait(&handledSignals, &signo) != 0) continue;  // fails only for a bad set
    CleanUpAndExit(signo);
}

}  // namespace

void InstallInterruptHandler() {
    sigemptyset(&handledSignals);
    for (const int signo : kInterruptSignals) {
        struct sigaction current = {};
        sigaction(signo, nullptr, &current);
        if (signo != SIGHUP || current.sa_handler != SIG_IGN) sigaddset(&handledSignals, signo);
    }
    const sigset_t set = handledSignals;
    pthread_sigmask(SIG_BLOCK, &set, nullptr);
    std::thread waiter(WaitForInterrupt);
    interruptThread = waiter.native_handle();  // valid for good: the thread never returns
    waiter.detach();
    struct sigaction forward = {};
    forward.sa_handler = ForwardToInterruptThread;
    forward.sa_mask = set;
    forward.sa_flags = SA_RESTART;
    for (const int signo : kInterruptSignals)
        if (sigismember(&set, signo)) sigaction(signo, &forward, nullptr);
}

TemporariesLock::TemporariesLock() : lock_(Registry().mutex) {}

void TemporariesLock::Register(const std::string& path) { Registry().paths.push_back(path); }

void TemporariesLock::RegisterChild(int pid) { Registry().children.push_back(pid); }

void TemporariesLock::UnregisterChild(int pid) { std::erase(Registry().children, pid_t(pid)); }

void TemporariesLock::Unregister(const std::string& path) {
    std::vector<std::string>& paths = Registry().paths;
    const auto found = std::find(paths.rbegin(), paths.rend(), path);
    if (found != paths.rend()) paths.erase(std::next(found).base());
}

}  // namespace rtrt
