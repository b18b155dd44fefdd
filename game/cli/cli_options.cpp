#include "game/cli/cli_options.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <regex>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "engine/core/output_file.h"
#include "game/runtime/world.h"
#include "game/scene/scene_file.h"

namespace rtrt {

void ParseSize(const std::string& text, uint32_t* width, uint32_t* height) {
    // Decimal digits only: stoul had taken a sign, spaces and negatives that wrapped around.
    static const std::regex kSize("([0-9]{1,9})x([0-9]{1,9})");
    std::smatch m;
    if (!std::regex_match(text, m, kSize))
        throw InputError("--size", "",
                         "expected WIDTHxHEIGHT such as 1920x1080, got \"" + text + "\"");
    const unsigned long w = std::stoul(m[1].str()), h = std::stoul(m[2].str());
    if (w < 1 || h < 1 || w > 16384 || h > 16384)
        throw InputError("--size", "", "width and height must be between 1 and 16384, got " + text);
    *width = uint32_t(w);
    *height = uint32_t(h);
}

// "N" or "A:B" read into *first and *end, unchecked; false when the text is neither.
static bool SplitFrames(const std::string& text, int* first, int* end) {
    // Split by hand: std::regex recurses once per character, and a long argument would overflow
    // the stack.
    const size_t colon = text.find(':');
    const std::string a = text.substr(0, colon);
    const std::string b = colon == std::string::npos ? "" : text.substr(colon + 1);
    auto digits = [](const std::string& part) {
        return !part.empty() && part.find_first_not_of("0123456789") == std::string::npos;
    };
    if (!digits(a) || (colon != std::string::npos && !digits(b))) return false;
    // Any number of digits: one past the last frame stands for all beyond.
    auto frame = [](const std::string& part) {
        const size_t start = std::min(part.find_first_not_of('0'), part.size());
        const std::string significant = part.substr(start);
        if (significant.empty()) return 0;
        return significant.size() > 8 ? kMaxFrames + 1
                                      : std::min(std::stoi(significant), kMaxFrames + 1);
    };
    *first = colon != std::string::npos ? frame(a) : 0;
    *end = colon != std::string::npos ? frame(b) : frame(a);
    return true;
}

bool ParseFrames(const std::string& text, int* first, int* end) {
    return SplitFrames(text, first, end) && *first < *end && *end <= kMaxFrames;
}

std::string FramesProblem(const std::string& text) {
    int first = 0, end = 0;
    if (text.empty()) return "give the frames: N (0 to N-1) or A:B (A to B-1), e.g. 0:480";
    if (!SplitFrames(text, &first, &end))
        return "expected N (frames 0 to N-1) or A:B (frames A to B-1), e.g. 0:480";
    if (end > kMaxFrames) return "frames end at 10,000,000 at the latest";
    if (first >= end)
        return text.find(':') == std::string::npos
                   ? "N is how many frames: at least 1"
                   : "A:B renders frames A to B-1, so A must be below B";
    return "";
}

namespace {

// A whole number in decimal, leading zeros dropped: CLI11 reads integers in C's base 0, so "017"
// was 15, "0x10" 16, and "-18446744073709551612" wrapped to 4 in an unsigned option.
CLI::Validator DecimalInteger(bool signedType) {
    return CLI::Validator(
        [signedType](std::string& value) -> std::string {
            const bool negative = signedType && !value.empty() && value[0] == '-';
            const bool plus = !value.empty() && value[0] == '+';
            const size_t start = negative || plus ? 1 : 0;
            const bool decimal = value.size() > start &&
                                 value.find_first_not_of("0123456789", start) == std::string::npos;
            if (!decimal)
                return "expected a whole number" + std::string(signedType ? "" : " >= 0") +
                       " in decimal digits, got \"" + value + "\"";
            const size_t first = std::min(value.find_first_not_of('0', start), value.size() - 1);
            const std::string magnitude = value.substr(first);
            // Beyond the 32 bits every whole-number option holds: said so, where the conversion
            // had failed with the value alone as its message.
            const std::string bound = !signedType ? "4294967295"
                                      : negative  ? "2147483648"
                                                  : "2147483647";
            if (magnitude.size() > bound.size() ||
                (magnitude.size() == bound.size() && magnitude > bound))
                return "\"" + value + "\" is beyond the " + (negative ? "smallest" : "largest") +
                       " whole number this option takes (" + (negative ? "-" : "") + bound + ")";
            value = (negative && magnitude != "0" ? "-" : "") + magnitude;
            return "";
        },
        "");
}

// A number in decimal notation (or inf or nan, which the range checks refuse by name): strtod's
// hexadecimal floats ("0x10" was 16) are not what a user of --fps means.
CLI::Validator DecimalNumber() {
    static const std::regex kDecimal(R"([+-]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][+-]?[0-9]+)?)");
    static const std::regex kWord(R"([+-]?(inf|infinity|nan)([(][^)]*[)])?)", std::regex::icase);
    return CLI::Validator(
        [](std::string& value) -> std::string {
            // Bounded before matching: std::regex recurses once per character.
            constexpr size_t kLongestNumber = 400;
            if (value.size() <= kLongestNumber &&
                (std::regex_match(value, kDecimal) || std::regex_match(value, kWord)))
                return "";
            return "expected a number in decimal notation, got \"" + value + "\"";
        },
        "");
}

// A text value that says something: an empty one (a script's unset variable) had meant the
// option's default, so that `--size ""` rendered at 1280x720 and `fetch-models --dir ""`
// fetched into the default folder.
CLI::Validator NonEmptyText() {
    return CLI::Validator(
        [](std::string& value) -> std::string {
            return value.empty() ? "an empty value: give one, or leave the option out" : "";
        },
        "");
}

}  // namespace

void AddExitStatusHelp(CLI::App& app) {
    static const std::string kInterrupted =
        "130, 143, 129, 131: stopped by SIGINT, SIGTERM, SIGHUP, SIGQUIT (finished outputs are "
        "kept, unfinished ones removed).";
    static const std::string kStatuses =
        "Exit status: 0 success; 1 the work failed (a GPU, I/O or memory error, a failed write); "
        "2 bad input (an option, a scene, a model, an output path); " +
        kInterrupted;
    const std::string own = app.get_footer();
    // A command that lists its own statuses (farm's 3) keeps them and gets the signals' only.
    if (own.find("Exit status") != std::string::npos)
        app.footer(own + " " + kInterrupted);
    else
        app.footer(own.empty() ? kStatuses : own + "\n" + kStatuses);
    for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
        AddExitStatusHelp(*sub);
}

void CheckOptionValues(CLI::App& app) {
    for (CLI::Option* option : app.get_options()) {
        if (option->get_type_size() == 0) continue;  // a flag
        const std::string type = option->get_type_name();
        const std::string base = type.substr(0, type.find(':'));
        if (base == "INT" || base == "UINT")
            option->transform(DecimalInteger(base == "INT"));
        else if (base == "FLOAT")
            option->transform(DecimalNumber());
        else if (base == "TEXT")
            option->transform(NonEmptyText());
    }
    for (CLI::App* command : app.get_subcommands({})) CheckOptionValues(*command);
}

CLI::Validator FiniteRange(double min, double max) {
    char range[64];
    std::snprintf(range, sizeof(range), "[%g, %g]", min, max);
    const std::string text = range;
    return CLI::Validator(
        [min, max, text](std::string& value) -> std::string {
            double number = 0.0;
            if (!CLI::detail::lexical_cast(value, number)) return "expected a number, got " + value;
            if (!std::isfinite(number) || number < min || number > max)
                return value + " is not a finite number in " + text;
            return "";
        },
        "NUMBER in " + text);
}

void RefuseOutputsOverInputs(const CLI::App& app) {
    struct Named {
        std::string option, path;
    };
    std::vector<Named> outputs, inputs;
    for (const CLI::App* level = &app; level;) {
        for (const CLI::Option* option : level->get_options()) {
            const std::string name = option->get_name();
            const bool positional = option->get_lnames().empty() && option->get_snames().empty();
            const bool output =
                name == "--output" || name == "--csv" || name == "--manifest" || name == "--record";
            const bool scenes = positional || name == "--scenes";  // bench split's
            if (!output && !scenes && name != "--script") continue;
            for (const std::string& path : option->results()) {
                if (path.empty()) continue;
                (output ? outputs : inputs).push_back({name, path});
                // A scene given by name is the file it names (RTRT_ASSET_DIR's or the tree's).
                if (scenes)
                    if (const std::string file = ScenePathFor(path); file != path)
                        inputs.push_back({name, file});
            }
        }
        const std::vector<CLI::App*> chosen = level->get_subcommands();
        level = chosen.empty() ? nullptr : chosen.front();
    }
    for (size_t k = 0; k < outputs.size(); ++k) {
        std::vector<Named> others(outputs.begin(), outputs.begin() + long(k));
        others.insert(others.end(), inputs.begin(), inputs.end());
        for (const Named& other : others)
            if (NameTheSameFile(outputs[k].path, other.path))
                throw InputError(
                    outputs[k].option, outputs[k].path,
                    "is also " +
                        (other.option.rfind("--", 0) == 0 ? other.option : "the input file") +
                        " (" + other.path + "), which would be written over; name another file");
    }
}

CLI::Validator WritableFile() {
    return CLI::Validator(
        [](std::string& path) -> std::string {
            try {
                CheckOutputPath(path);
            } catch (const InputError& e) {
                return path + ": " + e.Reason();
            }
            return "";
        },
        "FILE");
}

void AddOutputOptions(CLI::App* command, OutputOptions* options) {
    command
        ->add_option("--exposure", options->exposureEv,
                     "Exposure in EV (stops), in place of the scene's own, before the tone map")
        ->check(FiniteRange(-20.0, 20.0));
    command
        ->add_option("--tone-map", options->toneMap,
                     "pbr_neutral (Khronos PBR Neutral), aces or clamp (default: the scene's; "
                     "8-bit outputs, EXR and PFM stay linear)")
        ->check(CLI::IsMember({"pbr_neutral", "aces", "clamp"}));
}

void AddGpusOption(CLI::App* command, std::string* gpus) {
    command
        ->add_option("--gpus", *gpus,
                     "CUDA: split each frame's rows over N GPUs (or all), shares following each "
                     "GPU's trace time; the first GPU shows or writes the frame")
        ->capture_default_str();
}

GpuSplit ResolveGpus(const std::string& gpus, Backend backend) {
    GpuSplit split;
    // One GPU (also written 01) is the current device, as without the option.
    if (gpus.find_first_not_of('0') != std::string::npos &&
        gpus.substr(gpus.find_first_not_of('0')) == "1")
        return split;
    std::string why;
    if (!ChooseGpus(gpus, &split.devices, &why)) throw InputError("--gpus", gpus, why);
    if (backend != Backend::kCuda && split.devices.size() > 1)
        throw InputError("--gpus", gpus,
                         "splitting frames over GPUs needs the CUDA back end; use --backend cuda");
    if (split.devices.size() == 1) split.devices.clear();
    return split;
}

void AddTraversalOption(CLI::App* command, std::string* traversal) {
    command
        ->add_option("--traversal", *traversal,
                     "CUDA, scenes of 64 instances or more: nested (a BLAS loop in each TLAS "
                     "leaf), single (one loop over both levels) or auto (frames on one GPU "
                     "measure both as they play and keep the faster; otherwise nested); the "
                     "image is the same")
        ->check(CLI::IsMember({"auto", "nested", "single"}))
        ->capture_default_str();
}

void CheckTraversalBackend(const std::string& traversal, Backend backend) {
    if (backend == Backend::kCuda || traversal == "auto") return;
    throw InputError("--traversal", traversal,
                     "nested and single are the CUDA back end's traversals, and this command "
                     "runs on the CPU back end (which has one): use --backend cuda on a machine "
                     "with a CUDA device, or leave --traversal out");
}

void AddPhysicsSolverOption(CLI::App* command, std::string* solver) {
    command
        ->add_option("--physics-solver", *solver,
                     "Where the rigid bodies' contacts are solved: cpu (every core) or gpu (the "
                     "first CUDA device; the same result)")
        ->check(CLI::IsMember({"cpu", "gpu"}))
        ->capture_default_str();
}

void CheckPhysicsSolver(const std::string& solver) {
    if (solver != "gpu") return;
    std::string why;
    if (!physics::GpuContactSolver::Create(&why))
        throw InputError("--physics-solver", solver,
                         "cannot solve contacts on the GPU: " + why + "; use --physics-solver cpu");
}

void ApplyPhysicsSolver(const std::string& solver, World& world) {
    if (solver != "gpu") return;
    try {
        world.SolveContactsOnGpu();
    } catch (const std::runtime_error& e) {
        throw InputError("--physics-solver", solver,
                         std::string(e.what()) + "; use --physics-solver cpu");
    }
}

OutputTransform ResolveOutput(OutputTransform scene, const OutputOptions& options) {
    // A scene of display colours is written clamped: an exposure or a tone map of its display
    // values was neither that image nor the linear pipeline's (the scene file refuses them too).
    if (scene.srgbEncode == 0) {
        const std::string linear =
            "applies to linear colours, and this scene's are display values: add \"colours\": "
            "\"linear\" to the scene file (its colours are then light, tone mapped and "
            "sRGB-encoded)";
        if (options.exposureEv) {
            char ev[32];
            std::snprintf(ev, sizeof(ev), "%g", double(*options.exposureEv));
            throw InputError("--exposure", ev, linear);
        }
        if (!options.toneMap.empty()) throw InputError("--tone-map", options.toneMap, linear);
    }
    if (options.exposureEv) scene.exposureEv = *options.exposureEv;
    if (!options.toneMap.empty()) ParseToneMap(options.toneMap.c_str(), &scene.toneMap);
    return scene;
}

}  // namespace rtrt
