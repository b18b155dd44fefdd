#include "engine/core/child_process.h"

#include <fcntl.h>
#include <pthread.h>
#include <spawn.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>

#include "engine/core/interrupt.h"

extern char** environ;

namespace rtrt {
namespace {

// posix_spawn cannot set a child's parent-death signal (PR_SET_PDEATHSIG), so the parent names
// itself here and the child, an rtrt, sets the signal on itself (EndWithParent).
constexpr const char* kParentPidVariable = "RTRT_PARENT_PID";

// rtrt's environment with the options' variables set on top, as NAME=VALUE strings.
std::vector<std::string> Environment(const ChildOptions& options) {
    std::map<std::string, std::string> overrides = options.environment;
    if (options.endWithParent) overrides[kParentPidVariable] = std::to_string(::getpid());
    std::vector<std::string> env;
    for (char** entry = environ; *entry; ++entry) {
        const std::string text = *entry;
        const std::string name = text.substr(0, text.find('='));
        // The parent rtrt's own parent is not the child's: passed on, it would end the child.
        if (!overrides.count(name) && name != kParentPidVariable) env.push_back(text);
    }
    for (const auto& [name, value] : overrides) env.push_back(name + "=" + value);
    return env;
}

std::vector<char*> Pointers(std::vector<std::string>& strings) {
    std::vector<char*> pointers;
    for (std::string& s : strings) pointers.push_back(s.data());
    pointers.push_back(nullptr);
    return pointers;
}

void CloseIfOpen(int* fd) {
    if (*fd >= 0) ::close(*fd);
    *fd = -1;
}

}  // namespace

ChildProcess::ChildProcess(const std::vector<std::string>& argv, const ChildOptions& options) {
    int in[2] = {-1, -1}, out[2] = {-1, -1};
    if ((options.pipeStdin && ::pipe2(in, O_CLOEXEC) != 0) ||
        (options.pipeStdout && ::pipe2(out, O_CLOEXEC) != 0)) {
        error_ = std::strerror(errno);
        for (int fd : {in[0], in[1], out[0], out[1]})
            if (fd >= 0) ::close(fd);
        return;
    }
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    if (options.pipeStdin) posix_spawn_file_actions_adddup2(&actions, in[0], STDIN_FILENO);
    if (options.pipeStdout) posix_spawn_file_actions_adddup2(&actions, out[1], STDOUT_FILENO);
    if (options.quietStderr)
        posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
    if (options.ownProcessGroup && !options.pipeStdin)
        posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    posix_spawnattr_t attributes;
    posix_spawnattr_init(&attributes);
    sigset_t none, interrupts;
    sigemptyset(&none);
    sigemptyset(&interrupts);
    sigaddset(&interrupts, SIGINT);
    sigaddset(&interrupts, SIGTERM);
    sigaddset(&interrupts, SIGPIPE);  // rtrt blocks it around its own writes to a pipe
    posix_spawnattr_setsigmask(&attributes, &none);
    posix_spawnattr_setsigdefault(&attributes, &interrupts);
    short flags = POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF;
    if (options.ownProcessGroup) {
        posix_spawnattr_setpgroup(&attributes, 0);  // a group named by the child's own id
        flags |= POSIX_SPAWN_SETPGROUP;
    }
    posix_spawnattr_setflags(&attributes, flags);

    std::vector<std::string> args = argv;
    std::vector<std::string> env = Environment(options);
    std::vector<char*> argp = Pointers(args), envp = Pointers(env);
    // Registered under the lock it is started in: an interrupt either comes first (and nothing
    // starts) or knows the child.
    TemporariesLock lock;
    const int failed =
        ::posix_spawnp(&pid_, args[0].c_str(), &actions, &attributes, argp.data(), envp.data());
    if (failed == 0) lock.RegisterChild(pid_);
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attributes);
    CloseIfOpen(&in[0]);
    CloseIfOpen(&out[1]);
    if (failed != 0) {
        pid_ = -1;
        error_ = std::strerror(failed);
        CloseIfOpen(&in[1]);
        CloseIfOpen(&out[0]);
        return;
    }
    stdin_ = in[1];
    stdout_ = out[0];
}

ChildProcess::~ChildProcess() {
    CloseInput();
    Wait();
}

bool ChildProcess::WriteInput(const void* data, size_t size) {
    // A child that exits early closes the pipe: the write fails with EPIPE instead of SIGPIPE
    // ending rtrt, which is blocked on this thread for the write and consumed if it came.
    sigset_t pipeSignal, previous;
    sigemptyset(&pipeSignal);
    sigaddset(&pipeSignal, SIGPIPE);
    pthread_sigmask(SIG_BLOCK, &pipeSignal, &previous);
    const char* bytes = static_cast<const char*>(data);
    bool broken = false;
    while (size > 0 && stdin_ >= 0) {
        const ssize_t put = ::write(stdin_, bytes, size);
        if (put < 0 && errno == EINTR) continue;
        if (put <= 0) {
            broken = true;
            break;
        }
        bytes += put;
        size -= size_t(put);
    }
    if (broken) {
        const timespec now = {0, 0};
        while (sigtimedwait(&pipeSignal, nullptr, &now) == SIGPIPE) {
        }
    }
    pthread_sigmask(SIG_SETMASK, &previous, nullptr);
    return size == 0;
}

void ChildProcess::CloseInput() { CloseIfOpen(&stdin_); }

int ChildProcess::Wait(std::string* output) {
    if (pid_ <= 0) return status_ < 0 ? 127 : status_;
    CloseInput();
    if (stdout_ >= 0) {
        char buffer[4096];
        for (;;) {
            const ssize_t got = ::read(stdout_, buffer, sizeof(buffer));
            if (got < 0 && errno == EINTR) continue;
            if (got <= 0) break;
            if (output) output->append(buffer, size_t(got));
        }
        CloseIfOpen(&stdout_);
    }
    // The child is unregistered after it has ended but before it is reaped, so that an
    // interrupt never signals a stranger that was given its process id.
    siginfo_t ended{};
    while (::waitid(P_PID, id_t(pid_), &ended, WEXITED | WNOWAIT) < 0 && errno == EINTR) {
    }
    {
        TemporariesLock lock;
        lock.UnregisterChild(pid_);
    }
    int status = 0;
    pid_t waited;
    while ((waited = ::waitpid(pid_, &status, 0)) < 0 && errno == EINTR) {
    }
    pid_ = 0;
    if (waited < 0) {  // the child is not ours to wait for (SIGCHLD ignored): no status to trust
        error_ = std::strerror(errno);
        status_ = 127;
    } else {
        status_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    }
    return status_;
}

int RunProgram(const std::vector<std::string>& argv, std::string* output,
               const ChildOptions& options, std::string* error) {
    ChildOptions o = options;
    o.pipeStdout = o.pipeStdout || output != nullptr;
    ChildProcess child(argv, o);
    const int status = child.Wait(output);
    if (error) *error = child.Error();
    return status;
}

bool ProgramOnPath(const std::string& program) {
    if (program.find('/') != std::string::npos) return ::access(program.c_str(), X_OK) == 0;
    const char* path = std::getenv("PATH");
    std::string dirs = path ? path : "/usr/local/bin:/usr/bin:/bin";
    size_t start = 0;
    while (start <= dirs.size()) {
        const size_t end = std::min(dirs.find(':', start), dirs.size());
        const std::string dir = end > start ? dirs.substr(start, end - start) : ".";
        const std::string candidate = dir + "/" + program;
        struct stat info;
        if (::stat(candidate.c_str(), &info) == 0 && S_ISREG(info.st_mode) &&
            ::access(candidate.c_str(), X_OK) == 0)
            return true;
        start = end + 1;
    }
    return false;
}

void EndWithParent() {
    const char* text = std::getenv(kParentPidVariable);
    if (!text) return;
    char* end = nullptr;
    errno = 0;
    const long parent = std::strtol(text, &end, 10);
    if (errno != 0 || end == text || *end != '\0' || parent <= 1) return;
    ::prctl(PR_SET_PDEATHSIG, SIGTERM);
    // A parent that ended before the request sends nothing: the child has been handed to
    // another process already, and signals itself. (The farm starts rtrt itself, /proc/self/exe,
    // so the named parent is the direct one; kill(parent, 0) would take a dead, unreaped farm for
    // a live one.)
    if (::getppid() == pid_t(parent)) return;
    ::kill(::getpid(), SIGTERM);
    for (;;) ::pause();  // until the interrupt thread has cleaned up and exited
}

}  // namespace rtrt
