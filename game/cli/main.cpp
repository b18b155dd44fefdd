#include <algorithm>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "bench/bench_commands.h"
#include "engine/core/error.h"
#include "engine/core/interrupt.h"
#include "game/cli/commands.h"

namespace {

// Levenshtein distance, for "did you mean".
size_t EditDistance(const std::string& a, const std::string& b) {
    std::vector<size_t> row(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
        size_t diagonal = row[0];
        row[0] = i;
        for (size_t j = 1; j <= b.size(); ++j) {
            const size_t above = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
            diagonal = above;
        }
    }
    return row[b.size()];
}

// The first argument names no command: say so, with the nearest command if one is close.
bool ReportUnknownCommand(const CLI::App& app, int argc, char** argv) {
    if (argc < 2 || argv[1][0] == '-') return false;
    const std::string given = argv[1];
    std::string nearest, names;
    size_t best = 3;  // farther than two edits is no suggestion
    for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
        const std::string& name = sub->get_name();
        if (name == given) return false;
        names += (names.empty() ? "" : ", ") + name;
        if (const size_t d = EditDistance(given, name); d < best) {
            best = d;
            nearest = name;
        }
    }
    std::fprintf(stderr, "rtrt: error: '%s' is not an rtrt command%s (commands: %s; rtrt --help)\n",
                 given.c_str(),
                 nearest.empty() ? "" : ("; did you mean '" + nearest + "'?").c_str(),
                 names.c_str());
    return true;
}

}  // namespace

int main(int argc, char** argv) {
    rtrt::InstallInterruptHandler();  // before any thread starts
    CLI::App app{"rtrt: a real-time ray tracer (CUDA and CPU back ends)", "rtrt"};
    app.set_version_flag("--version", "rtrt 0.1.0");
    app.require_subcommand(1);
    int exitCode = rtrt::kExitOk;
    rtrt::AddRenderCommand(app, &exitCode);
    rtrt::AddPlayCommand(app, &exitCode);
    rtrt::AddConvertCommand(app, &exitCode);
    rtrt::AddInfoCommand(app, &exitCode);
    rtrt::AddFetchModelsCommand(app, &exitCode);
    rtrt::AddFarmCommand(app, &exitCode);
    rtrt::AddBenchCommand(app, &exitCode);
    if (ReportUnknownCommand(app, argc, argv)) return rtrt::kExitBadInput;
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        // --help and --version print what was asked for; a bad command line is one line, as
        // every other error is.
        if (e.get_exit_code() == 0) return app.exit(e);
        std::fprintf(stderr, "rtrt: error: %s (--help lists the options)\n", e.what());
        return rtrt::kExitBadInput;
    } catch (const rtrt::InputError& e) {
        std::fprintf(stderr, "rtrt: error: %s\n", e.what());
        return rtrt::kExitBadInput;
    } catch (const rtrt::OutputError& e) {
        std::fprintf(stderr, "rtrt: error: %s\n", e.what());
        return rtrt::kExitFailure;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "rtrt: error: %s\n", e.what());
        return rtrt::kExitFailure;
    }
    return exitCode;
}
