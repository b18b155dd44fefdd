#pragma once
// Other programs run by rtrt (Slurm's sbatch and squeue, ffmpeg, the model script): started with
// posix_spawn, so nothing runs between fork and exec, with SIGINT and SIGTERM back to their
// default action in the child (rtrt's own mask survives exec, see interrupt.h).
#include <sys/types.h>

#include <map>
#include <string>
#include <vector>

namespace rtrt {

struct ChildOptions {
    bool pipeStdin = false;    // the parent writes the child's standard input (WriteInput)
    bool pipeStdout = false;   // the parent reads the child's standard output (Wait returns it)
    bool quietStderr = false;  // the child's standard error goes to /dev/null
    std::map<std::string, std::string> environment;  // set on top of rtrt's own
    // The child, an rtrt that calls EndWithParent, gets SIGTERM when this process ends, however
    // it ends (SIGKILL too), instead of going on as an orphan. Linux sends it when the thread
    // that started the child ends, so that thread must outlive the child.
    bool endWithParent = false;
    // The child leads a process group of its own, which an interrupt rtrt hands on reaches
    // whole: a script's own programs stop with it (a signal to the script alone waits until its
    // program ends, and that program runs on). Its standard input is /dev/null unless piped, as
    // a group other than the terminal's must not read the terminal.
    bool ownProcessGroup = false;
};

class ChildProcess {
  public:
    // Starts ARGV[0], looked up on PATH. Throws nothing: Started() says whether it ran, and
    // Error() why not (e.g. "No such file or directory" for a program that is not installed).
    ChildProcess(const std::vector<std::string>& argv, const ChildOptions& options = {});
    ~ChildProcess();  // closes the pipes and waits, so that no child is left behind
    ChildProcess(const ChildProcess&) = delete;
    ChildProcess& operator=(const ChildProcess&) = delete;

    bool Started() const { return pid_ > 0; }
    const std::string& Error() const { return error_; }

    // Writes all of DATA to the child's input; false when the child has closed it (it exited).
    bool WriteInput(const void* data, size_t size);
    void CloseInput();

    // Waits for the child: its exit status, 128 + the signal that ended it, or 127 when it could
    // not be started. *OUTPUT gets what it printed when pipeStdout was asked for.
    int Wait(std::string* output = nullptr);

  private:
    pid_t pid_ = -1;
    int stdin_ = -1, stdout_ = -1;
    int status_ = -1;
    std::string error_;
};

// Runs ARGV to its end: its status (as Wait), and what it printed on standard output. When it
// could not be started (127), *ERROR, if given, says why.
int RunProgram(const std::vector<std::string>& argv, std::string* output = nullptr,
               const ChildOptions& options = {}, std::string* error = nullptr);

// Whether PROGRAM is on PATH (an executable file), as a shell would find it.
bool ProgramOnPath(const std::string& program);

// In an rtrt started with ChildOptions::endWithParent: asks for SIGTERM when the parent ends,
// and ends the process as SIGTERM does (interrupt.h) when the parent has ended already. Does
// nothing in a process started otherwise.
void EndWithParent();

}  // namespace rtrt
