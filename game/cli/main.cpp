#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <new>
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

// A word where a command is expected (rtrt COMMAND, rtrt bench SUBCOMMAND) that names none: say
// so, with the nearest command if one is close, and list them. Options there (rtrt --bogus) are
// named too: CLI11 would only say that a subcommand is required.
bool ReportUnknownCommand(const CLI::App& app, int argc, char** argv) {
    const CLI::App* level = &app;
    std::string path = "rtrt";
    for (int i = 1; i < argc; ++i) {
        const auto subcommands = level->get_subcommands([](const CLI::App*) { return true; });
        if (subcommands.empty()) return false;  // a command's own arguments: CLI11 checks them
        const std::string given = argv[i];
        if (given.starts_with("-")) {
            if (level->get_option_no_throw(given.substr(0, given.find('='))) != nullptr)
                return false;
            std::fprintf(stderr, "rtrt: error: '%s' is not an option of %s (%s --help)\n",
                         given.c_str(), path.c_str(), path.c_str());
            return true;
        }
        std::string nearest, names;
        const CLI::App* match = nullptr;
        size_t best = 3;  // farther than two edits is no suggestion
        for (const CLI::App* sub : subcommands) {
            const std::string& name = sub->get_name();
            if (name == given) match = sub;
            names += (names.empty() ? "" : ", ") + name;
            if (const size_t d = EditDistance(given, name); d < best) {
                best = d;
                nearest = name;
            }
        }
        if (match == nullptr) {
            std::fprintf(stderr,
                         "rtrt: error: '%s' is not %s command%s (commands: %s; %s --help)\n",
                         given.c_str(), path == "rtrt" ? "an rtrt" : ("a '" + path + "'").c_str(),
                         nearest.empty() ? "" : ("; did you mean '" + nearest + "'?").c_str(),
                         names.c_str(), path.c_str());
            return true;
        }
        level = match;
        path += " " + given;
    }
    return false;
}

// What a command printed on stdout must arrive: a report redirected to a full disk had left an
// empty file and exit 0. Flushed and closed here, as coreutils do, so that a late write error
// (a full disk, NFS on close) is the command's failure.
int WithStdoutChecked(int exitCode) {
    errno = 0;
    const bool failed = std::fflush(stdout) != 0 || std::ferror(stdout) != 0;
    const int error = errno;
    if (std::fclose(stdout) != 0 || failed) {
        const int why = error != 0 ? error : errno;
        // The command's own outputs are finished and kept: said so, since exit 1 elsewhere means
        // that nothing is left at a failed output.
        std::fprintf(stderr, "rtrt: error: stdout: %s%s\n",
                     why != 0 ? std::strerror(why) : "a write to it failed",
                     exitCode == rtrt::kExitOk
                         ? " (the command's work is done, any files it wrote are complete; only "
                           "what it printed was lost)"
                         : "");
        return exitCode == rtrt::kExitOk ? rtrt::kExitFailure : exitCode;
    }
    return exitCode;
}

int RunCommandLine(int argc, char** argv) {
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
    rtrt::CheckOptionValues(app);
    rtrt::AddExitStatusHelp(app);
    app.parse_complete_callback([&app] { rtrt::RefuseOutputsOverInputs(app); });
    if (ReportUnknownCommand(app, argc, argv)) return rtrt::kExitBadInput;
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        // --help and --version print what was asked for; a bad command line is one line, as
        // every other error is.
        if (e.get_exit_code() == 0) return app.exit(e);
        std::fprintf(stderr, "rtrt: error: %s (--help lists the options)\n",
                     rtrt::WithoutControlCharacters(e.what()).c_str());
        return rtrt::kExitBadInput;
    } catch (const rtrt::InputError& e) {
        std::fprintf(stderr, "rtrt: error: %s\n", e.what());
        return rtrt::kExitBadInput;
    } catch (const rtrt::OutputError& e) {
        std::fprintf(stderr, "rtrt: error: %s\n", e.what());
        return rtrt::kExitFailure;
    } catch (const std::bad_alloc&) {
        // Said in words: "std::bad_alloc" named neither the cause nor exit 1's meaning here.
        std::fprintf(stderr,
                     "rtrt: error: out of memory: the command needs more memory than this process "
                     "may have (see ulimit -v and the machine's free memory); a smaller scene, "
                     "size or model would fit\n");
        return rtrt::kExitFailure;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "rtrt: error: %s\n", rtrt::WithoutControlCharacters(e.what()).c_str());
        return rtrt::kExitFailure;
    }
    return exitCode;
}

}  // namespace

int main(int argc, char** argv) { return WithStdoutChecked(RunCommandLine(argc, argv)); }
