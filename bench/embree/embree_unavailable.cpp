// `rtrt bench embree` in a build without Embree 3: the command exists and says how to get it.
#include "bench/bench_commands.h"
#include "engine/core/error.h"

namespace rtrt {

void AddEmbreeBench(CLI::App& bench, int* exitCode) {
    CLI::App* cmd =
        bench.add_subcommand("embree",
                             "CPU frame of the paper scene through rtrt's BVH and through Embree 3 "
                             "(needs a build with libembree-dev)");
    cmd->allow_extras();
    cmd->callback([exitCode] {
        std::fprintf(stderr,
                     "rtrt bench embree: this rtrt was built without Embree 3. Install it "
                     "(apt-get install libembree-dev), then configure and build again.\n");
        *exitCode = kExitFailure;
    });
}

}  // namespace rtrt
