// `rtrt play SCENE --headless --frames N [--fps F] -o DIR/frame_%04d.png`: plays a scene on a
// fixed time step and writes every frame. The window (without --headless) comes with the
// interactive runtime.
#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <regex>
#include <string>
#include <vector>

#include "engine/core/child_process.h"
#include "engine/core/content_hash.h"
#include "engine/core/error.h"
#include "engine/core/input_file.h"
#include "engine/core/output_file.h"
#include "engine/core/timer.h"
#include "engine/render_rt/frame_renderer.h"
#include "engine/render_rt/renderer.h"
#include "game/assets/image_io.h"
#include "game/assets/video_writer.h"
#include "game/cli/commands.h"
#include "game/cli/progress_bar.h"
#include "game/farm/farm_job.h"
#include "game/farm/frame_manifest.h"
#include "game/runtime/world.h"
#include "game/scene/scene_file.h"
#if defined(RTRT_HAVE_WINDOW)
#include "game/app/interactive_app.h"
#endif

namespace rtrt {
namespace {

struct PlayOptions {
    std::vector<std::string> scenes;
    std::string output;
    std::string size;
    std::string backend = "auto";
    std::string gpus = "1";
    std::string physicsSolver = "cpu";
    std::string record, script;
    std::string manifest;       // headless: a line per finished frame, with its checksum
    std::string sceneChecksum;  // headless: the scene files' checksum (HashFiles) must be this
    bool headless = false;
    bool noVsync = false;
    bool finishStages = false;
    std::string frames;  // N, or A:B (headless)
    uint32_t spp = 1;
    bool sppGiven = false;  // --spp on the command line, its default value included
    double fps = 60.0;
    OutputOptions display;  // exposure and tone map
};

// The output pattern must hold exactly one printf integer field (%d, %04d, ...).
std::string FramePath(const std::string& pattern, int frame) {
    char buffer[4096];
    std::snprintf(buffer, sizeof(buffer), pattern.c_str(), frame);
    return buffer;
}

// The field's width has at most two digits: a frame number needs ten, and a wider field would
// make names longer than file systems allow (or than FramePath's buffer holds).
void CheckPattern(const std::string& pattern) {
    static const std::regex kField("%0?[0-9]{0,2}d");
    const auto fields = std::distance(std::sregex_iterator(pattern.begin(), pattern.end(), kField),
                                      std::sregex_iterator());
    const auto percents = std::count(pattern.begin(), pattern.end(), '%');
    if (pattern.find("%%") != std::string::npos)
        throw InputError("--output", pattern,
                         "a % of its own (%%) cannot be in the pattern: its only % is the frame "
                         "number field's, e.g. out/frame_%04d.png");
    // A manifest lists frames one a line, their fields split by tabs.
    if (std::any_of(pattern.begin(), pattern.end(),
                    [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; }))
        throw InputError("--output", "",
                         "the pattern has a control character (a tab or a line end): name the "
                         "frames without one");
    if (fields != 1 || percents != 1 || pattern.size() > 2000)
        throw InputError("--output", "",
                         "expected a pattern with one frame number field of at most two "
                         "digits' width, such as out/frame_%04d.png, got \"" +
                             pattern + "\"");
    // Every frame goes into one folder, checked before the first frame; and a manifest names
    // frames by file name alone.
    const size_t field = pattern.find('%');
    if (pattern.find('/', field) != std::string::npos)
        throw InputError("--output", pattern,
                         "the frame number must be in the file name, not in a folder's, e.g. "
                         "out/frame_%04d.png");
}

// InputError naming OPTION when FILE is the name of one of the frames [first, end) the pattern
// makes: the check of outputs against inputs compared the pattern itself, so a manifest named
// like frame 1 got the frame appended to it, and a scene named so was written over.
void RefuseFrameOver(const std::string& pattern, int first, int end, const std::string& option,
                     const std::string& file) {
    if (file.empty()) return;
    const size_t slash = pattern.rfind('/');
    const std::string name = slash == std::string::npos ? pattern : pattern.substr(slash + 1);
    const size_t field = name.find('%'), fieldEnd = name.find('d', field);
    // The file's name read as the pattern's: its literal parts around digits for the field.
    const auto escaped = [](const std::string& text) {
        std::string out;
        for (char c : text) {
            if (std::string("\\^$.|?*+()[]{}").find(c) != std::string::npos) out += '\\';
            out += c;
        }
        return out;
    };
    // Digits as any printf field writes them, padded with zeros or spaces (%4d).
    const std::regex named(escaped(name.substr(0, field)) + "( *-?[0-9]{1,9})" +
                           escaped(name.substr(fieldEnd + 1)));
    // The file a link leads to is the one a frame would be written over.
    const std::string target = FollowOutputLinks(file);
    const size_t targetSlash = target.rfind('/');
    const std::string fileName =
        targetSlash == std::string::npos ? target : target.substr(targetSlash + 1);
    std::smatch m;
    if (!std::regex_match(fileName, m, named)) return;
    const int frame = std::stoi(m[1].str());
    if (frame < first || frame >= end || !NameTheSameFile(FramePath(pattern, frame), target))
        return;
    throw InputError("--output", pattern,
                     "frame " + std::to_string(frame) + " would be written over " + option + " (" +
                         file + "); name the frames or that file otherwise");
}

// The most pixels the window opens with on the CPU back end unless --size says otherwise.
constexpr uint32_t kCpuWindowPixels = 640 * 360;

void RunWindowed(const PlayOptions& o) {
#if defined(RTRT_HAVE_WINDOW)
    WindowOptions w;
    w.scenes = o.scenes;
    w.backend = o.backend;
    Backend chosen = Backend::kCpu;
    if (ChooseBackend(o.backend, &chosen, nullptr)) w.gpus = ResolveGpus(o.gpus, chosen);
    CheckPhysicsSolver(o.physicsSolver);
    w.contactsOnGpu = o.physicsSolver == "gpu";
    if (!o.size.empty()) {
        ParseSize(o.size, &w.width, &w.height);
    } else {
        // The first scene's image size, checked here so that a bad file fails before a window.
        const LoadedScene first = LoadSceneFile(o.scenes[0]);
        w.width = first.width.value_or(1280);
        w.height = first.height.value_or(720);
        // The CPU back end traces a 1280x720 frame in a third of a second on a small machine:
        // the window opens at a quarter of the pixels, which stays interactive, and says so.
        Backend backend = Backend::kCpu;
        std::string why;
        if (ChooseBackend(o.backend, &backend, &why) && backend == Backend::kCpu &&
            w.width * w.height > kCpuWindowPixels) {
            const double shrink = std::sqrt(double(kCpuWindowPixels) / (w.width * w.height));
            w.width = std::max(1u, uint32_t(w.width * shrink));
            w.height = std::max(1u, uint32_t(w.height * shrink));
            std::printf(
                "rtrt: the CPU back end renders the window at %ux%u to stay interactive; "
                "--size WxH chooses another size\n",
                w.width, w.height);
        }
    }
    for (const std::string& scene : o.scenes) LoadSceneFile(scene);
    w.vsync = !o.noVsync;
    w.finishStages = o.finishStages;
    w.record = o.record;
    if (!o.record.empty()) CheckRecordPath(o.record);
    // Its screenshots may go into --record's folder, which the window makes once it opens.
    if (!o.script.empty())
        w.script = InputScript::Load(o.script, IsVideoPath(o.record) ? "" : o.record);
    int first = 0, end = 0;
    if (!o.frames.empty() && o.frames.find(':') != std::string::npos)
        throw InputError("--frames", o.frames,
                         "the window takes a frame count N (A:B ranges are for --headless)");
    if (!o.frames.empty() && !ParseFrames(o.frames, &first, &end))
        throw InputError("--frames", o.frames, FramesProblem(o.frames));
    w.frames = end;
    // An event the window never reaches (a screenshot after the last frame) would be dropped.
    if (w.script && end > 0 && w.script->LastEvent() >= end)
        throw InputError(o.script, "",
                         "has an event at frame " + std::to_string(w.script->LastEvent()) +
                             ", but --frames " + o.frames + " closes the window after frame " +
                             std::to_string(end - 1) + ": give more frames, or leave --frames out");
    w.fps = float(o.fps);
    w.exposureEv = o.display.exposureEv;
    w.toneMap = o.display.toneMap;
    RunWindow(w);
#else
    (void)o;
    throw InputError("play", "",
                     "this rtrt was built without the window (libglfw3-dev, libgl-dev and "
                     "libimgui-dev were missing at configure time); add --headless --frames N -o "
                     "DIR/frame_%04d.png");
#endif
}

// Options of one mode given to the other would do nothing; they are refused instead.
void CheckModeOptions(const PlayOptions& o) {
    if (o.headless) {
        if (!o.record.empty())
            throw InputError("--record", "",
                             "records the window; headless frames go to -o (rtrt farm --assemble "
                             "or ffmpeg makes a video of them)");
        if (!o.script.empty())
            throw InputError("--script", "", "scripts the window's input; it is not headless");
        if (o.noVsync) throw InputError("--no-vsync", "", "is for the window; it is not headless");
        if (o.finishStages)
            throw InputError("--finish-stages", "", "is for the window; it is not headless");
    } else {
        if (o.sppGiven)
            throw InputError("--spp", "", "is for --headless frames; the window traces one sample");
        if (!o.manifest.empty()) throw InputError("--manifest", "", "is for --headless frames");
        if (!o.sceneChecksum.empty())
            throw InputError("--scene-checksum", "", "is for --headless frames");
        if (!o.output.empty())
            throw InputError("--output", "",
                             "is for --headless frames; the window records with --record");
    }
}

// The file PATH leads to (links followed) as device and inode; {0, 0} where there is none.
std::pair<uint64_t, uint64_t> FileIdentity(const std::string& path) {
    struct stat info {};
    if (::stat(path.c_str(), &info) != 0) return {0, 0};
    return {uint64_t(info.st_dev), uint64_t(info.st_ino)};
}

void RunPlay(PlayOptions o) {
    if (o.scenes.empty()) o.scenes = {"default"};
    CheckModeOptions(o);
    if (!o.headless) return RunWindowed(o);
    if (o.scenes.size() != 1)
        throw InputError("play", "", "--headless plays one scene; give exactly one");
    int first = 0, end = 0;
    if (!ParseFrames(o.frames, &first, &end))
        throw InputError("--frames", o.frames, FramesProblem(o.frames));
    if (o.output.empty())
        throw InputError("--output", "", "give where frames go, e.g. out/frame_%04d.png");
    CheckPattern(o.output);
    RefuseFrameOver(o.output, first, end, "--manifest", o.manifest);
    RefuseFrameOver(o.output, first, end, "the scene file", ScenePathFor(o.scenes[0]));
    // The last frame's name is the longest; every frame's is checked again as it is written.
    CheckImagePath(FramePath(o.output, first));
    CheckImagePath(FramePath(o.output, end - 1));
    if (!o.manifest.empty()) CheckManifestPath(o.manifest);
    const LoadedScene loaded = LoadSceneFile(o.scenes[0]);
    // The files the scene named (models, a glTF file's buffers and images), known only now.
    for (const std::string& asset : AssetFilesRead())
        RefuseFrameOver(o.output, first, end, "a file of the scene", asset);
    CheckSceneChecksum(o.scenes[0], o.sceneChecksum);
    RenderSettings settings;
    settings.width = loaded.width.value_or(1280);
    settings.height = loaded.height.value_or(720);
    if (!o.size.empty()) ParseSize(o.size, &settings.width, &settings.height);
    CheckImageSize(o.output, settings.width, settings.height);
    settings.maxDepth = loaded.scene.maxDepth;
    settings.samplesPerPixel = o.spp;
    Backend backend;
    std::string why;
    if (!ChooseBackend(o.backend, &backend, &why))
        throw InputError("--backend", o.backend, why + "; use --backend cpu");

    CheckPhysicsSolver(o.physicsSolver);
    const OutputTransform transform = ResolveOutput(loaded.output, o.display);
    World world(loaded);
    ApplyPhysicsSolver(o.physicsSolver, world);
    const std::unique_ptr<FrameRenderer> renderer =
        MakeFrameRenderer(backend, world.Scene(), {}, {}, ResolveGpus(o.gpus, backend));
    const float dt = float(1.0 / o.fps);
    world.PlayAtFixedFrames(dt);
    // Frames before A are played, not traced: the simulation and every update of the frame
    // renderer (TLAS and BLAS refits, rebuild decisions) happen as in a full run, so frame A on
    // is byte for byte what a run from frame 0 writes.
    Stopwatch replay;
    for (int i = 1; i < first; ++i) {  // frame i is the scene after i steps
        world.Advance(dt);
        renderer->Update(world.Scene(), world.Changes());
    }
    if (first > 1) {
        renderer->Finish();
        const double ms = replay.Milliseconds();
        std::printf("rtrt: replayed frames 0 to %d untraced in %.1f ms (%.3f ms per frame)\n",
                    first - 1, ms, ms / (first - 1));
    }
    Image frame;
    double total = 0.0;
    std::map<std::pair<uint64_t, uint64_t>, int> writtenFiles;  // device and inode: frame
    for (int i = first; i < end; ++i) {
        Stopwatch timer;
        if (i > 0) {
            world.Advance(dt);
            renderer->Update(world.Scene(), world.Changes());
        }
        renderer->Trace(world.Scene(), settings, &frame);
        bool written = false;
        auto stopped = [&](const std::string& file, const std::string& reason) {
            // What is kept, and the command that goes on from the frame that failed.
            const int last = written ? i : i - 1;
            std::string kept = "no frame was written";
            if (last == first) kept = "frame " + std::to_string(first) + " is written and kept";
            if (last > first)
                kept = "frames " + std::to_string(first) + " to " + std::to_string(last) +
                       " are written and kept";
            if (written) kept += " (frame " + std::to_string(i) + " is not in the manifest)";
            return OutputError(file, reason + "; " + kept + ", and --frames " + std::to_string(i) +
                                         ":" + std::to_string(end) + " goes on from here");
        };
        try {
            // A frame's name that leads to a frame this run wrote (a link to it) would replace
            // that frame: the run had ended with exit 0 and one frame short.
            if (const auto earlier = writtenFiles.find(FileIdentity(FramePath(o.output, i)));
                earlier != writtenFiles.end() && earlier->first.second != 0)
                throw OutputError(FramePath(o.output, i),
                                  "leads to frame " + std::to_string(earlier->second) +
                                      ", written by this run (a link?); remove it");
            WriteImage(FramePath(o.output, i), frame, transform);
            written = true;
            writtenFiles[FileIdentity(FramePath(o.output, i))] = i;
            if (!o.manifest.empty()) AppendToManifest(o.manifest, i, FramePath(o.output, i));
        } catch (const OutputError& e) {
            throw stopped(e.File(), e.Reason());
        } catch (const InputError& e) {
            // A later frame's path found unusable (a folder of its name, a folder made read-only
            // since the start): an output failure of this run, not bad input.
            throw stopped(e.File(), e.Reason());
        }
        total += timer.Milliseconds();
        char what[64];
        std::snprintf(what, sizeof(what), "frames, %.1f ms/frame", total / (i - first + 1));
        DrawProgressBar("play", i - first + 1, end - first, what);
    }
    std::printf(
        "rtrt: wrote frames %d to %d to %s (%ux%u, %g fps time step, %zu instances at the "
        "end)\n",
        first, end - 1, o.output.c_str(), settings.width, settings.height, o.fps,
        world.Scene().instances.size());
}

}  // namespace

void AddPlayCommand(CLI::App& app, int* exitCode) {
    auto options = std::make_shared<PlayOptions>();
    CLI::App* cmd =
        app.add_subcommand("play", "Play a scene: animation, physics, spawners, camera path");
    cmd->add_option("scenes", options->scenes,
                    "Scene files (.json, .gltf, .glb), names of rtrt's own scenes (e.g. "
                    "demo_crowd), or \"default\" (the built-in scene, also when none is named); "
                    "in the window PageDown/PageUp switch between them");
    cmd->add_flag("--headless", options->headless, "Render to files instead of a window");
    cmd->add_option("--frames", options->frames,
                    "Headless: frames to write, N (0 to N-1) or A:B (A to B-1, each exactly as a "
                    "run from frame 0 writes it); window: frames to show before closing");
    CLI::Option* spp =
        cmd->add_option("--spp", options->spp,
                        "Samples per pixel, n x n stratified (1, 4, 9, 16...), for offline quality")
            ->check(CLI::IsMember({1u, 4u, 9u, 16u, 25u, 36u, 49u, 64u}))
            ->capture_default_str();
    cmd->add_option("--manifest", options->manifest,
                    "Headless: append a line per finished frame to this file (frame, file, "
                    "bytes, XXH3-64 checksum), as rtrt farm's tasks do");
    cmd->add_option("--scene-checksum", options->sceneChecksum,
                    "Headless: play only if the checksum (hex, XXH3-64) of the scene file and "
                    "every file it brings in is this, as rtrt farm's tasks do");
    cmd->add_option("--record", options->record,
                    "Window: record every frame shown (fixed time step) to a video (.mp4, .mkv, "
                    ".mov: H.264 through ffmpeg) or to DIR/frame_NNNNN.png");
    cmd->add_option("--script", options->script,
                    "Window: scripted input, for tests (see game/app/input_script.h)")
        ->check(CLI::ExistingFile);
    cmd->add_flag("--no-vsync", options->noVsync, "Window: start with vsync off (V toggles it)");
    cmd->add_flag("--finish-stages", options->finishStages,
                  "Window: wait for the GPU after each display stage, so that the stage medians "
                  "printed at the end are each stage's own cost (slower; for profiling)");
    cmd->add_option("--fps", options->fps,
                    "Frames per second of scene time (the fixed step is 1/fps)")
        ->check(FiniteRange(1.0, 1000.0))
        ->capture_default_str();
    cmd->add_option("-o,--output", options->output, "Frame file pattern, e.g. out/frame_%04d.png");
    cmd->add_option("--size", options->size, "Image size WIDTHxHEIGHT (default: the scene's)");
    cmd->add_option("--backend", options->backend, "auto (CUDA when usable), cpu or cuda")
        ->check(CLI::IsMember({"auto", "cpu", "cuda"}))
        ->capture_default_str();
    AddGpusOption(cmd, &options->gpus);
    AddPhysicsSolverOption(cmd, &options->physicsSolver);
    AddOutputOptions(cmd, &options->display);
    cmd->callback([options, exitCode, spp] {
        options->sppGiven = spp->count() > 0;
        EndWithParent();  // a farm's task ends with its farm (rtrt farm --local)
        RunPlay(*options);
        *exitCode = kExitOk;
    });
}

}  // namespace rtrt
