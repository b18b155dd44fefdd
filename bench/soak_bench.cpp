// `rtrt bench soak`: spawns and despawns entities for many frames through the World and a frame
// renderer, as a long interactive session does — spheres, and every tenth a deforming box (its
// Deformation released and reused) — and samples the process's resident memory (and the GPU's
// memory in use) every --every frames. After the warm-up the samples must stay within 5% of each
// other; the table and JSON say whether they did. A benchmark, not a test: it runs for minutes.
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <deque>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "bench/backend_option.h"
#include "bench/bench_commands.h"
#include "bench/bench_report.h"
#include "bench/gpu_trace_timing.h"
#include "engine/core/error.h"
#include "engine/core/timer.h"
#include "engine/render_rt/frame_renderer.h"
#include "game/assets/procedural_shapes.h"
#include "game/runtime/world.h"
#include "game/scene/default_scene.h"

namespace rtrt {
namespace {

struct SoakOptions {
    std::string backend = "auto";
    int frames = 10000;
    int perFrame = 100;
    int alive = 1000;
    int every = 100;
    int warmup = 1000;
    std::string output;
};

// The process's resident set, in bytes (the second field of /proc/self/statm, in pages).
size_t ResidentBytes() {
    std::ifstream statm("/proc/self/statm");
    size_t pages = 0, resident = 0;
    statm >> pages >> resident;
    return resident * size_t(sysconf(_SC_PAGESIZE));
}

double Spread(const std::vector<double>& v) {
    if (v.empty()) return 0.0;
    const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
    return *lo > 0.0 ? (*hi - *lo) / *lo : 0.0;
}

// Whether memory stayed flat.
bool RunSoak(const SoakOptions& o) {
    const bool gpu = o.backend == "cuda";
    const LoadedScene loaded = MakeDefaultLoadedScene();
    World world(loaded);
    const Sphere sphere{vec3(0.0f), 0.3f};
    const uint32_t sphereBlas =
        world.AddBlas(std::make_shared<const Blas>(BuildSphereBlas({&sphere, 1})));
    const TriangleMesh box = MakeBoxMesh(vec3(0.5f));
    const uint32_t boxBlas = world.AddBlas(std::make_shared<const Blas>(BuildTriangleBlas(box)));
    auto boxMesh = std::make_shared<DeformableMesh>();
    boxMesh->rest = box;
    const uint32_t boxDeform = world.AddDeformableMesh(boxMesh);
    Material m;
    m.diffuse = vec3(0.7f, 0.5f, 0.3f);
    const uint32_t material = world.AddMaterial(m);
    const std::unique_ptr<FrameRenderer> renderer =
        MakeFrameRenderer(gpu ? Backend::kCuda : Backend::kCpu, world.Scene());
    RenderSettings settings;
    settings.width = 64;
    settings.height = 36;
    settings.maxDepth = 2;
    std::deque<ecs::Entity> live;
    std::vector<double> host, device, frameMs;
    uint64_t spawned = 0;
    std::printf(
        "rtrt bench soak (%s back end): %d frames, %d spawns and despawns per frame, %d "
        "alive\n%8s %10s %12s %12s %10s\n",
        o.backend.c_str(), o.frames, o.perFrame, o.alive, "frame", "spawned", "host MiB", "GPU MiB",
        "frame ms");
    for (int f = 1; f <= o.frames; ++f) {
        Stopwatch timer;
        for (int k = 0; k < o.perFrame; ++k, ++spawned) {
            EntityDesc d;
            d.materialId = material;
            d.local.translation =
                vec3(float(spawned % 37) * 0.2f - 3.6f, 0.5f, float(spawned % 29) * 0.2f - 3.0f);
            d.blasId = sphereBlas;
            if (spawned % 10 == 0) {  // a deforming box: its Deformation is reused after despawn
                d.blasId = boxBlas;
                d.deformableMesh = int32_t(boxDeform);
                d.procedural.kind = ProceduralDeformKind::kWave;
                d.procedural.amplitude = 0.1f;
                d.procedural.wavelength = 0.5f;
            }
            live.push_back(world.Spawn(d));
        }
        while (live.size() > size_t(o.alive)) {
            world.Remove(live.front());
            live.pop_front();
        }
        world.Advance(1.0f / 60.0f);
        renderer->Update(world.Scene(), world.Changes());
        renderer->Trace(world.Scene(), settings, nullptr);
        renderer->Finish();
        frameMs.push_back(timer.Milliseconds());
        if (f % o.every != 0) continue;
        const double hostMiB = double(ResidentBytes()) / (1024.0 * 1024.0);
        size_t deviceBytes = 0;
        const bool hasDevice = gpu && DeviceMemoryInUse(&deviceBytes);
        const double deviceMiB = double(deviceBytes) / (1024.0 * 1024.0);
        if (f > o.warmup) {
            host.push_back(hostMiB);
            if (hasDevice) device.push_back(deviceMiB);
        }
        std::printf("%8d %10llu %12.1f %12s %10.3f\n", f, (unsigned long long)spawned, hostMiB,
                    hasDevice ? std::to_string(deviceMiB).substr(0, 8).c_str() : "-",
                    frameMs.back());
        std::fflush(stdout);
    }
    const bool flat = Spread(host) <= 0.05 && Spread(device) <= 0.05;
    std::printf("after frame %d: host memory spread %.2f%%, GPU memory spread %s: %s\n", o.warmup,
                100.0 * Spread(host),
                device.empty() ? "-" : (std::to_string(100.0 * Spread(device)) + "%").c_str(),
                flat ? "flat within 5%" : "NOT flat within 5%");
    if (!o.output.empty()) {
        nlohmann::json report = {{"machine", BenchMachine(gpu)},
                                 {"backend", o.backend},
                                 {"frames", o.frames},
                                 {"spawns", spawned},
                                 {"alive", o.alive},
                                 {"host_mib_after_warmup", host},
                                 {"gpu_mib_after_warmup", device},
                                 {"host_spread", Spread(host)},
                                 // null without GPU samples (a CPU run): no spread was measured.
                                 {"gpu_spread", device.empty() ? nlohmann::json(nullptr)
                                                               : nlohmann::json(Spread(device))},
                                 {"flat_within_5_percent", flat}};
        WriteReport(o.output, report);
        std::printf("rtrt: wrote %s\n", o.output.c_str());
    }
    return flat;
}

}  // namespace

void AddSoakBench(CLI::App& bench, int* exitCode) {
    auto o = std::make_shared<SoakOptions>();
    CLI::App* cmd = bench.add_subcommand(
        "soak", "Spawn and despawn entities for many frames; host and GPU memory must stay flat");
    cmd->footer(
        "Exit status: 0 memory stayed flat within 5%; 1 it did not, or the work failed (a GPU, "
        "I/O or memory error, a failed write); 2 bad input (an option, an output path).");
    AddBackendOption(cmd, &o->backend);
    cmd->add_option("--frames", o->frames, "Frames to play")
        ->check(CLI::Range(1, 10000000))
        ->capture_default_str();
    cmd->add_option("--per-frame", o->perFrame, "Spawns (and, once full, despawns) per frame")
        ->check(CLI::Range(1, 100000))
        ->capture_default_str();
    cmd->add_option("--alive", o->alive, "Entities alive at once")
        ->check(CLI::Range(1, 10000000))
        ->capture_default_str();
    cmd->add_option("--every", o->every, "Frames between memory samples")
        ->check(CLI::Range(1, 1000000))
        ->capture_default_str();
    cmd->add_option("--warmup", o->warmup, "Frames before the samples that must stay flat")
        ->check(CLI::Range(0, 10000000))
        ->capture_default_str();
    cmd->add_option("-o,--output", o->output, "Write the results as JSON here")
        ->check(WritableFile());
    cmd->callback([o, exitCode] {
        ResolveBackendOption(&o->backend);
        // Memory is sampled at frames past --warmup that --every divides: with fewer than two
        // samples nothing says whether it stayed flat (it had reported "flat within 5%").
        int samples = 0;
        for (int f = o->warmup + 1; f <= o->frames && samples < 2; ++f)
            samples += f % o->every == 0;
        if (samples < 2)
            throw InputError("--frames", "",
                             std::to_string(o->frames) + " frames take " + std::to_string(samples) +
                                 " memory sample(s) after --warmup " + std::to_string(o->warmup) +
                                 " every " + std::to_string(o->every) +
                                 " frames; at least 2 tell whether memory stays flat: give more "
                                 "--frames, or a smaller --warmup or --every");
        // A soak whose memory grew fails, so that a script can tell (it had exited 0 either way).
        *exitCode = RunSoak(*o) ? kExitOk : kExitFailure;
    });
}

}  // namespace rtrt
