#include "game/app/interactive_app.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "engine/bvh/tlas/tlas.h"
#include "engine/core/error.h"
#include "engine/core/output_file.h"
#include "engine/core/timer.h"
#include "engine/render_rt/frame_renderer.h"
#include "engine/render_rt/renderer.h"
#include "game/app/camera_controller.h"
#include "game/app/controls.h"
#include "game/app/cuda_gl_frame.h"
#include "game/app/frame_display.h"
#include "game/app/gl.h"
#include "game/app/input_script.h"
#include "game/app/overlay.h"
#include "game/app/spawn_palette.h"
#include "game/app/window.h"
#include "game/assets/image_io.h"
#include "game/assets/video_writer.h"
#include "game/scene/scene_file.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

namespace rtrt {
namespace {

constexpr float kSpawnDistance = 4.0f;

class App {
  public:
    explicit App(const WindowOptions& o)
        : o_(o),
          window_(int(o.width), int(o.height), "rtrt", o.vsync),
          overlay_(window_.Handle()),
          camera_(Camera{}, 1.0f) {
        std::string why;
        Backend backend;
        if (!ChooseBackend(o.backend, &backend, &why))
            throw InputError("--backend", o.backend, why + "; use --backend cpu");
        model_.cudaAvailable = CudaBackendAvailable(nullptr);
        model_.useCuda = backend == Backend::kCuda;
        model_.glRenderer = window_.Renderer();
        script_ = o.script;
        if (!o.record.empty() && !IsVideoPath(o.record)) CreateOutputFolder(o.record);
        LoadScene(0);
    }

    int Run() {
        Stopwatch clock;
        for (frame_ = 0; !window_.ShouldClose(); ++frame_) {
            if (o_.frames > 0 && frame_ >= o_.frames) break;
            // A script ends the window after its last event, unless --frames says when.
            if (script_ && o_.frames == 0 && frame_ > script_->LastFrame()) break;
            const double wallDt = clock.Milliseconds() * 1e-3;
            clock.Restart();
            Stopwatch frameTimer;
            window_.PollEvents();
            InputScript::Effects effects;
            if (script_) effects = script_->Apply(frame_, window_.GetInput());
            if (effects.quit) window_.RequestClose();
            HandleInput(float(wallDt));
            const bool fixedStep = script_ || !o_.record.empty();
            float dt = fixedStep ? 1.0f / o_.fps : float(std::min(wallDt, 0.1));
            dt *= model_.timeScale;
            if (model_.paused) dt = stepOnce_ ? model_.timeScale / o_.fps : 0.0f;
            stepOnce_ = false;
            // The first frame shows the scene as loaded, as play --headless's frame 0 does: a
            // recording lacked it, and each of its frames showed the headless frame after.
            if (frame_ == 0) dt = 0.0f;
            const FrameStats fs = world_->Advance(dt);
            model_.times.simulate = fs.simulateMs;
            model_.times.extract = fs.extractMs;
            RenderFrame();
            Stopwatch displayTimer;
            const ivec2 fb = window_.FramebufferSize();
            display_.Draw(fb.x, fb.y);
            FinishStage();
            model_.times.draw = displayTimer.Milliseconds();
            // Screenshots and recordings read back what the window shows, before the overlay.
            if (!effects.screenshots.empty() || screenshotKey_ || !o_.record.empty()) {
                const Image shown = FrameDisplay::ReadBack(fb.x, fb.y);
                for (const std::string& path : effects.screenshots) WriteImage(path, shown);
                if (screenshotKey_) {
                    TakeScreenshot(shown);
                    screenshotKey_ = false;
                }
                if (IsVideoPath(o_.record)) {
                    // The video keeps the first frame's size; a resized window is fitted to it.
                    if (!video_)
                        video_ = std::make_unique<VideoWriter>(o_.record, shown.width, shown.height,
                                                               o_.fps);
                    video_->AddFrame(shown);
                } else if (!o_.record.empty()) {
                    // As the video does: every frame the first one's size (F11, a resize).
                    if (recorded_ == 0) recordSize_ = {shown.width, shown.height};
                    WriteImage(o_.record + "/" + RecordedFrameName(recorded_++),
                               CentredOn(shown, recordSize_.x, recordSize_.y));
                }
            }
            Stopwatch stageTimer;
            overlay_.Draw(model_);
            FinishStage();
            model_.times.overlay = stageTimer.Milliseconds();
            stageTimer.Restart();
            window_.SwapBuffers();
            FinishStage();
            model_.times.swap = stageTimer.Milliseconds();
            model_.times.display = displayTimer.Milliseconds();
            model_.times.frame = frameTimer.Milliseconds();
            if (frame_ >= untimedUntil_ && timed_.size() < kTimedFrames)
                timed_.push_back(model_.times);
            model_.frameMs.push_back(float(model_.times.frame));
            if (model_.frameMs.size() > OverlayModel::kHistory) model_.frameMs.pop_front();
        }
        std::printf("rtrt: %d frames, %zu instances at the end, display: %s\n", frame_,
                    world_->Scene().instances.size(), model_.display.c_str());
        PrintStageMedians();
        if (video_) {
            video_->Finish();
            std::printf("rtrt: recorded %d frames to %s\n", video_->Frames(), o_.record.c_str());
        }
        return 0;
    }

  private:
    void FinishStage() const {
        if (o_.finishStages) glFinish();
    }

    // The stage medians printed at the end are of the scene and back end shown last.
    void RestartTiming() {
        timed_.clear();
        untimedUntil_ = frame_ + kUntimedFrames;
    }

    // Medians of the timed frames' stages: where a windowed frame's time goes.
    void PrintStageMedians() const {
        if (timed_.empty()) return;
        auto median = [&](double StageTimes::*stage) {
            std::vector<double> v;
            for (const StageTimes& t : timed_) v.push_back(t.*stage);
            return Median(std::move(v));
        };
        std::printf(
            "rtrt: medians of %zu frames, ms: frame %.3f | simulate %.3f extract %.3f | render "
            "deform %.3f BLAS %.3f upload %.3f TLAS %.3f trace %.3f | host present %.3f draw "
            "%.3f overlay %.3f swap %.3f\n",
            timed_.size(), median(&StageTimes::frame), median(&StageTimes::simulate),
            median(&StageTimes::extract), median(&StageTimes::deform), median(&StageTimes::blas),
            median(&StageTimes::upload), median(&StageTimes::tlas), median(&StageTimes::trace),
            median(&StageTimes::present), median(&StageTimes::draw), median(&StageTimes::overlay),
            median(&StageTimes::swap));
    }

    // Switching scenes (Page Up/Down): a scene that no longer loads (edited since the window
    // opened) is reported and the window stays on the one it shows; it had ended the session
    // and dropped its recording.
    void SwitchScene(size_t index) {
        std::unique_ptr<LoadedScene> next;
        try {
            next = std::make_unique<LoadedScene>(LoadSceneFile(o_.scenes[index]));
        } catch (const InputError& e) {
            std::fprintf(stderr, "rtrt: error: %s; staying on %s\n", e.what(),
                         model_.scene.c_str());
            return;
        }
        LoadScene(index, std::move(next));
    }

    // F12: the first rtrt-screenshot-N.png not there yet (an earlier run's stay). A screenshot
    // that cannot be written (a read-only folder, a full disk) is reported; it had ended the
    // session and taken its recording with it.
    void TakeScreenshot(const Image& shown) {
        std::string path;
        std::error_code ec;
        do {
            path = "rtrt-screenshot-" + std::to_string(screenshotCount_++) + ".png";
        } while (std::filesystem::exists(std::filesystem::symlink_status(path, ec)));
        try {
            WriteImage(path, shown);
            std::printf("rtrt: wrote %s\n", path.c_str());
        } catch (const std::runtime_error& e) {  // OutputError, or InputError (the path)
            std::fprintf(stderr, "rtrt: error: no screenshot: %s\n", e.what());
        }
    }

    void LoadScene(size_t index, std::unique_ptr<LoadedScene> next = nullptr) {
        if (!next) next = std::make_unique<LoadedScene>(LoadSceneFile(o_.scenes[index]));
        sceneIndex_ = index;
        renderer_.reset();
        world_.reset();
        loaded_ = std::move(next);
        world_ = std::make_unique<World>(*loaded_);
        if (o_.contactsOnGpu) world_->SolveContactsOnGpu();
        std::vector<std::string> notes;
        palette_ = std::make_unique<SpawnPalette>(*world_, &notes);
        for (const std::string& n : notes) std::printf("rtrt: %s\n", n.c_str());
        renderer_ = MakeFrameRenderer(model_.useCuda ? Backend::kCuda : Backend::kCpu,
                                      world_->Scene(), {}, {}, GpusFor(model_.useCuda));
        model_.scene = std::filesystem::path(o_.scenes[index]).filename().string();
        model_.frameMs.clear();  // another scene's frame times would mislead
        RestartTiming();
        model_.maxDepth = int(loaded_->scene.maxDepth);
        OutputTransform output = loaded_->output;
        if (o_.exposureEv) output.exposureEv = *o_.exposureEv;
        if (!o_.toneMap.empty()) ParseToneMap(o_.toneMap.c_str(), &output.toneMap);
        model_.exposureEv = output.exposureEv;
        model_.toneMap = int(output.toneMap);
        model_.srgb = output.srgbEncode != 0;
        // Flying speed: a quarter of the scene's size per second.
        Aabb bounds;
        std::vector<Aabb> blasBounds;
        for (const auto& b : world_->Scene().blases) blasBounds.push_back(b->bounds);
        for (const Aabb& b : InstanceWorldBounds(world_->Scene().instances, blasBounds))
            bounds.Grow(b);
        const float size = bounds.IsEmpty() ? 10.0f : glm::length(bounds.max - bounds.min);
        camera_ = CameraController(world_->Scene().camera, std::max(0.25f * size, 1.0f));
        cameraTaken_ = false;
        selected_ = {};
        std::printf("rtrt: playing %s (%zu instances, %s back end)\n", model_.scene.c_str(),
                    world_->Scene().instances.size(), model_.useCuda ? "cuda" : "cpu");
    }

    void SwitchBackend(bool useCuda) {
        const Backend backend = useCuda ? Backend::kCuda : Backend::kCpu;
        if (renderer_->Kind() == backend) return;
        model_.useCuda = useCuda;
        // The new renderer takes the scene as it is now: every record, a fresh TLAS.
        renderer_ = MakeFrameRenderer(backend, world_->Scene(), {}, {}, GpusFor(useCuda));
        interop_.Unregister();
        model_.frameMs.clear();  // the other back end's frame times would mislead
        RestartTiming();
    }

    // --gpus applies to the CUDA back end (the window switches back ends with a key).
    GpuSplit GpusFor(bool useCuda) const { return useCuda ? o_.gpus : GpuSplit{}; }

    Ray RayThroughMouse() const {
        const ivec2 fb = window_.FramebufferSize();
        int ww = 0, wh = 0;
        glfwGetWindowSize(window_.Handle(), &ww, &wh);
        const vec2 scale = vec2(fb) / vec2(std::max(ww, 1), std::max(wh, 1));
        const vec2 p = window_.GetInputConst().mouse * scale;
        const uint32_t x = uint32_t(std::clamp(p.x, 0.0f, float(fb.x - 1)));
        const uint32_t y = uint32_t(std::clamp(p.y, 0.0f, float(fb.y - 1)));
        return PrimaryRay(MakeCameraFrame(world_->Scene().camera, fb.x, fb.y), x, y, fb.x, fb.y);
    }

    // Whether the mouse is over the frame: a click outside it (a script's 1e38) picks nothing,
    // where the clamped position had picked what the frame's edge showed.
    bool MouseOverFrame() const {
        int ww = 0, wh = 0;
        glfwGetWindowSize(window_.Handle(), &ww, &wh);
        const vec2 m = window_.GetInputConst().mouse;
        return m.x >= 0.0f && m.y >= 0.0f && m.x < float(ww) && m.y < float(wh);
    }

    void Pick() {
        if (!MouseOverFrame()) {
            selected_ = ecs::Entity{};
            model_.selected.clear();
            return;
        }
        const Ray ray = RayThroughMouse();
        SceneHit hit{};
        const bool found = renderer_->Pick(ray, &hit);
        // The whole object: a glTF node's mesh moved alone is turned and scaled by its parent's
        // frame, and a skinned mesh's node does not move its skin at all.
        selected_ =
            found ? world_->ObjectRoot(world_->EntityOfInstance(hit.instance)) : ecs::Entity{};
        model_.selected.clear();
        if (selected_.IsNull()) return;
        const auto* local = world_->Registry().Get<physics::LocalTransform>(selected_);
        grabDistance_ = hit.t;
        grabOffset_ = local->translation - (ray.origin + hit.t * ray.dir);
        model_.selected =
            "instance " + std::to_string(hit.instance) + " at distance " + std::to_string(hit.t);
        std::printf("rtrt: picked instance %u at distance %.3f\n", hit.instance, hit.t);
    }

    void Drag() {
        const auto* local = world_->Registry().Get<physics::LocalTransform>(selected_);
        if (!local) return;
        const Ray ray = RayThroughMouse();
        world_->SetPose(selected_, ray.origin + grabDistance_ * ray.dir + grabOffset_,
                        local->rotation);
    }

    // Where a character spawned now stands (SpawnGround). It had stood on y = 0 under the point
    // ahead, below the view of most demos' cameras and in the air above demo_1000_instances's
    // floor.
    std::optional<vec3> GroundAhead() const {
        return SpawnGround(
            *world_, world_->Scene().camera, kSpawnDistance,
            [&](const Ray& ray, SceneHit* hit) { return renderer_->Pick(ray, hit); });
    }

    void Spawn(const char* name) {
        const SpawnKind* kind = palette_->Find(name);
        if (!kind) {
            std::printf("rtrt: no %s to spawn (its model was not fetched)\n", name);
            return;
        }
        const std::optional<vec3> ground = kind->gltf ? GroundAhead() : std::nullopt;
        selected_ = palette_->SpawnInFront(*world_, *kind, world_->Scene().camera, kSpawnDistance,
                                           ground ? &*ground : nullptr);
        model_.selected = std::string("a new ") + name;
        // A mirror (mostly reflective) shows its reflection only with a bounce to spare, glass
        // only with two (into the glass and out of it): the depth goes up to what the object
        // needs, and says so.
        const Material& m = world_->Scene().materials[kind->materialId];
        const int needed = m.transmissivity > 0.0f ? 3 : m.reflectivity >= 0.5f ? 2 : 1;
        if (!kind->gltf && model_.maxDepth < needed) {
            model_.maxDepth = needed;
            std::printf(
                "rtrt: max depth raised to %d so that the %s shows what it %s (- lowers it)\n",
                needed, name, m.transmissivity > 0.0f ? "refracts" : "reflects");
        }
    }

    void HandleInput(float wallDt) {
        Input& in = window_.GetInput();
        const bool scripted = script_.has_value();
        const bool uiMouse = !scripted && overlay_.WantsMouse();
        const bool uiKeys = !scripted && overlay_.WantsKeyboard();
        // Mouse first: a pick in the same frame as a delete uses the TLAS it was traced with.
        if (!uiMouse && in.leftPressed) Pick();
        if (!uiMouse && in.leftDown && !in.leftPressed && !selected_.IsNull() &&
            world_->Registry().Valid(selected_) && in.mouseDelta != vec2(0.0f))
            Drag();
        if (!uiKeys)
            for (int key : in.pressed)
                for (const Control& c : Controls())
                    if (c.key == key) Do(c.action);
        CameraInput ci;
        if (!uiKeys) {
            auto down = [&](int k) { return in.down[k] ? 1.0f : 0.0f; };
            ci.move = vec3(down(GLFW_KEY_D) - down(GLFW_KEY_A), down(GLFW_KEY_E) - down(GLFW_KEY_Q),
                           down(GLFW_KEY_W) - down(GLFW_KEY_S));
            ci.fast = in.down[GLFW_KEY_LEFT_SHIFT] || in.down[GLFW_KEY_RIGHT_SHIFT];
        }
        if (!uiMouse) {
            if (in.rightDown) ci.look = in.mouseDelta;
            ci.zoom = in.scroll;
        }
        if (ci.move != vec3(0.0f) || ci.look != vec2(0.0f) || ci.zoom != 0.0f) cameraTaken_ = true;
        if (cameraTaken_) {
            camera_.Update(ci, script_ ? 1.0f / o_.fps : wallDt);
            world_->OverrideCamera(camera_.Get());
        } else {
            camera_.Reset(world_->Scene().camera);  // follow the scene's camera path
        }
        SwitchBackend(model_.useCuda);  // the overlay's radio buttons
    }

    void Do(Action action) {
        auto flip = [](bool& b) { b = !b; };
        switch (action) {
            case Action::kSpawnSphere:
                return Spawn("sphere");
            case Action::kSpawnTeapot:
                return Spawn("teapot");
            case Action::kSpawnDragon:
                return Spawn("dragon");
            case Action::kSpawnGlassSphere:
                return Spawn("glass sphere");
            case Action::kSpawnMirrorBox:
                return Spawn("mirror box");
            case Action::kSpawnWalker:
                return Spawn("walker");
            case Action::kDeleteSelected:
                if (!selected_.IsNull() && world_->RemoveObject(selected_))
                    std::printf("rtrt: deleted\n");
                selected_ = {};
                model_.selected.clear();
                return;
            case Action::kRotateSelected:
                if (const auto* l = world_->Registry().Get<physics::LocalTransform>(selected_))
                    world_->SetPose(
                        selected_, l->translation,
                        glm::angleAxis(glm::radians(15.0f), vec3(0, 1, 0)) * l->rotation);
                return;
            case Action::kPause:
                return flip(model_.paused);
            case Action::kStep:
                stepOnce_ = true;
                return;
            case Action::kSlower:  // down to 1/1024: halving had reached 0, which ] could not undo
                model_.timeScale = std::max(model_.timeScale * 0.5f, 1.0f / 1024.0f);
                return;
            case Action::kFaster:
                model_.timeScale = std::min(model_.timeScale * 2.0f, 16.0f);
                return;
            case Action::kNextScene:
                return SwitchScene((sceneIndex_ + 1) % o_.scenes.size());
            case Action::kPreviousScene:
                return SwitchScene((sceneIndex_ + o_.scenes.size() - 1) % o_.scenes.size());
            case Action::kScreenshot:
                screenshotKey_ = true;
                return;
            case Action::kToggleHelp:
                return flip(model_.showHelp);
            case Action::kToggleOverlay:
                return flip(model_.show);
            case Action::kFullscreen:
                return window_.ToggleFullscreen();
            case Action::kVsync:
                return window_.SetVsync(!window_.Vsync());
            case Action::kOrbitMode:
                camera_.SetMode(camera_.GetMode() == CameraController::Mode::kFly
                                    ? CameraController::Mode::kOrbit
                                    : CameraController::Mode::kFly);
                cameraTaken_ = true;
                return;
            case Action::kShadows:
                return flip(model_.shadows);
            case Action::kReflection:
                return flip(model_.reflection);
            case Action::kRefraction:
                return flip(model_.refraction);
            case Action::kNextView:
                model_.view = (model_.view + 1) % 4;
                return;
            case Action::kDepthUp:
                model_.maxDepth = std::min(model_.maxDepth + 1, 8);
                return;
            case Action::kDepthDown:
                // A scene's deeper max_depth comes down to the keys' range at once.
                model_.maxDepth = std::clamp(model_.maxDepth - 1, 1, 8);
                return;
            case Action::kExposureUp:
                model_.exposureEv = std::min(model_.exposureEv + 0.5f, 20.0f);
                return;
            case Action::kExposureDown:
                model_.exposureEv = std::max(model_.exposureEv - 0.5f, -20.0f);
                return;
            case Action::kBackend:
                if (model_.cudaAvailable) model_.useCuda = !model_.useCuda;
                return;
            case Action::kQuit:
                return window_.RequestClose();
        }
    }

    RenderSettings Settings() const {
        const ivec2 fb = window_.FramebufferSize();
        RenderSettings s;
        s.width = uint32_t(std::max(fb.x, 1));
        s.height = uint32_t(std::max(fb.y, 1));
        s.maxDepth = uint32_t(model_.maxDepth);
        s.view = ViewMode(model_.view);
        // Textures are content, not an effect the overlay turns off.
        s.enabledFeatures = (model_.shadows ? kFeatureShadows : 0u) |
                            (model_.reflection ? kFeatureReflection : 0u) |
                            (model_.refraction ? kFeatureRefraction : 0u) | kFeatureTextures |
                            kFeaturePbr;
        return s;
    }

    // Traces the frame and puts it in the display's texture: on the GPU through CUDA-GL interop
    // when it works, otherwise (and on the CPU) through host memory.
    void RenderFrame() {
        const RenderScene& scene = world_->Scene();
        const RenderSettings s = Settings();
        const bool gpu = renderer_->Kind() == Backend::kCuda;
        // Views other than shaded are finished on the host (FinishView).
        const bool viaHost = !gpu || s.view != ViewMode::kShaded || interopFailed_;
        if (!viaHost && (display_.Resize(s.width, s.height) || !interop_.Registered())) {
            std::string why;
            if (!interop_.Register(display_.Texture(), &why)) {
                std::printf(
                    "rtrt: CUDA-GL interop is not available (%s); frames are copied through host "
                    "memory\n",
                    why.c_str());
                interopFailed_ = true;
                return RenderFrame();
            }
        }
        renderer_->Update(scene, world_->Changes());
        // GPU times (and the ray count) arrive a frame or two late rather than make this wait.
        RenderStats stats;
        renderer_->Trace(scene, s, viaHost ? &raw_ : nullptr, &stats);
        const FrameTimes& t = renderer_->Times();
        model_.times.deform = t.deformMs;
        model_.times.blas = t.blasMs;
        model_.times.deformed = t.deformed;
        model_.times.blasRebuilt = t.blasRebuilt;
        model_.times.upload = t.uploadMs;
        model_.times.tlas = t.tlasMs;
        model_.times.trace = t.traceMs;
        const uint32_t split = t.gpus > 1 ? t.gpus : 0;  // one GPU: its trace is the trace
        model_.times.gpuTrace.assign(t.gpuTraceMs.begin(), t.gpuTraceMs.begin() + split);
        model_.times.gpuRows.assign(t.gpuRows.begin(), t.gpuRows.begin() + split);
        model_.rays = t.rays;
        // Only the shaded view is radiance; the others are display values already.
        const OutputTransform output =
            s.view == ViewMode::kShaded
                ? OutputTransform{model_.exposureEv, ToneMap(model_.toneMap), model_.srgb ? 1u : 0u}
                : kDisplayValues;
        Stopwatch presentTimer;
        if (viaHost) {
            shown_ = FinishView(raw_, s.view);
            display_.Upload(shown_, output);
            model_.display = gpu ? "frames through host memory" : "CPU upload";
        } else {
            interop_.Present(renderer_->DeviceFrame(), s.width, s.height, output);
            model_.display = "CUDA-GL interop";
        }
        FinishStage();
        model_.times.present = presentTimer.Milliseconds();
        model_.backend = gpu ? "CUDA" : "CPU";
        model_.instances = scene.instances.size();
        model_.triangles = scene.TriangleCount();
        model_.tlasNodes = scene.instances.empty() ? 0 : 2 * scene.instances.size() - 1;
    }

    WindowOptions o_;
    Window window_;
    FrameDisplay display_;
    Overlay overlay_;
    CudaGlFrame interop_;
    bool interopFailed_ = false;
    std::optional<InputScript> script_;
    std::unique_ptr<LoadedScene> loaded_;
    std::unique_ptr<World> world_;
    std::unique_ptr<SpawnPalette> palette_;
    std::unique_ptr<FrameRenderer> renderer_;
    CameraController camera_;
    bool cameraTaken_ = false;
    OverlayModel model_;
    // Stage times of the frames after the first kUntimedFrames (start-up, first uploads), for
    // the medians printed at the end; at most kTimedFrames of them, so that a long session's
    // memory does not grow with it.
    static constexpr int kUntimedFrames = 30;
    static constexpr size_t kTimedFrames = 100000;
    std::vector<StageTimes> timed_;
    int untimedUntil_ = kUntimedFrames;  // the first frame timed_ takes
    Image raw_, shown_;
    ecs::Entity selected_;
    float grabDistance_ = 0.0f;
    vec3 grabOffset_{0.0f};
    size_t sceneIndex_ = 0;
    int frame_ = 0, recorded_ = 0, screenshotCount_ = 0;
    glm::uvec2 recordSize_{0, 0};         // of the first frame --record DIR wrote
    std::unique_ptr<VideoWriter> video_;  // --record to a video file
    bool stepOnce_ = false, screenshotKey_ = false;
};

}  // namespace

int RunWindow(const WindowOptions& options) { return App(options).Run(); }

}  // namespace rtrt
