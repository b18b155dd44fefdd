#include <cstdio>
#include <exception>

#include "bench/bench_commands.h"
#include "engine/core/error.h"
#include "game/cli/commands.h"

int main(int argc, char** argv) {
    CLI::App app{"rtrt: a real-time ray tracer (CUDA and CPU back ends)", "rtrt"};
    app.set_version_flag("--version", "rtrt 0.1.0");
    app.require_subcommand(1);
    int exitCode = rtrt::kExitOk;
    rtrt::AddRenderCommand(app, &exitCode);
    rtrt::AddPlayCommand(app, &exitCode);
    rtrt::AddConvertCommand(app, &exitCode);
    rtrt::AddInfoCommand(app, &exitCode);
    rtrt::AddBenchCommand(app, &exitCode);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        const int status = app.exit(e);
        return status == 0 ? rtrt::kExitOk : rtrt::kExitBadInput;
    } catch (const rtrt::InputError& e) {
        std::fprintf(stderr, "rtrt: error: %s\n", e.what());
        return rtrt::kExitBadInput;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "rtrt: error: %s\n", e.what());
        return rtrt::kExitFailure;
    }
    return exitCode;
}
