// `rtrt farm SCENE --frames A:B --shards K -o DIR`: a frame sequence rendered on a Slurm cluster as
// a job array (each element a share of the frames, `rtrt play --frames` on its node) and a job
// after it that assembles the video. Resumable: the folder's manifest says which frames are
// finished, and a rerun renders only what is missing or corrupt. `--status DIR` says what is done,
// `--assemble DIR` is the assembly job's own command, `--local` runs the same tasks here.
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/core/child_process.h"
#include "engine/core/content_hash.h"
#include "engine/core/error.h"
#include "engine/core/input_file.h"
#include "engine/core/output_file.h"
#include "engine/render_rt/render_settings.h"
#include "game/assets/image_io.h"
#include "game/cli/commands.h"
#include "game/cli/progress_bar.h"
#include "game/farm/farm_commands.h"
#include "game/farm/farm_job.h"
#include "game/farm/farm_lock.h"
#include "game/farm/frame_manifest.h"
#include "game/farm/job_folder.h"
#include "game/farm/shard_plan.h"
#include "game/farm/slurm_queue.h"
#include "game/farm/video_assembly.h"
#include "game/scene/scene_file.h"

namespace rtrt {
namespace {
namespace fs = std::filesystem;

// `rtrt farm --status` while frames, the video or the contact sheet are still missing.
constexpr int kExitIncomplete = 3;
// How long --assemble waits for another run's lock on the folder.
constexpr int kAssembleLockWaitSeconds = 300;

struct FarmOptions {
    std::string scene, output, frames, size, backend, format, partition, timeLimit;
    std::string status, assemble;
    int shards = 1, cpusPerTask = 1;
    uint32_t spp = 1;
    double fps = 60.0;
    bool gpu = false, dryRun = false, local = false, ignoreQueue = false;
};

std::string RtrtPath() {
    std::error_code ec;
    const fs::path self = fs::read_symlink("/proc/self/exe", ec);
    return ec ? std::string("rtrt") : self.string();
}

// The command that submits (or resumes) JOB, for messages.
std::string FarmCommandLine(const FarmJob& job, const std::string& extra = "") {
    const FarmFrames& f = job.frames;
    std::string line = "rtrt farm " + ShellQuote(f.scene) + " --frames " + RangeText(f.frames) +
                       " --size " + std::to_string(f.width) + "x" + std::to_string(f.height) +
                       " --spp " + std::to_string(f.spp) + " --backend " + f.backend +
                       " --shards " + std::to_string(job.scheduling.shards);
    if (f.fps != 60.0) line += " --fps " + FpsText(f.fps);
    line += " --format " + f.format;
    const FarmScheduling& s = job.scheduling;
    if (s.gpu) line += " --gpu";
    if (!s.partition.empty()) line += " --partition " + ShellQuote(s.partition);
    if (!s.timeLimit.empty()) line += " --time " + ShellQuote(s.timeLimit);
    if (s.cpusPerTask != 1) line += " --cpus-per-task " + std::to_string(s.cpusPerTask);
    return line + " -o " + ShellQuote(job.folder) + extra;
}

void ReportStaleTemporaries(const FarmFolderLock& lock) {
    if (const int removed = lock.RemoveStaleTemporaries(); removed > 0)
        std::printf("rtrt farm: removed %d unfinished file%s left by processes that are gone\n",
                    removed, removed == 1 ? "" : "s");
}

// " --local" for a job that was never submitted to Slurm: its command goes on rendering here.
std::string LocalFlag(const FarmJob& job) { return job.submissions.empty() ? " --local" : ""; }

void DrawCheckProgress(int done, int total) {
    DrawProgressBar("farm", done, total, "frames checked");
}

FrameCheck CheckAndReport(const FarmJob& job) {
    const int total = job.frames.frames.Count();
    const FrameCheck check = CheckFrames(job, total >= 1000 ? DrawCheckProgress : nullptr);
    std::printf("rtrt farm: %s: %zu of %d frames done", job.folder.c_str(), check.done.size(),
                total);
    if (!check.missing.empty())
        std::printf(", %zu missing (%s)", check.missing.size(), FramesText(check.missing).c_str());
    if (!check.corrupt.empty())
        std::printf(", %zu corrupt (%s: not the checksum the manifest holds)", check.corrupt.size(),
                    FramesText(check.corrupt).c_str());
    std::printf("\n");
    return check;
}

// The job the options describe, checked: the scene loads, the folder can hold it.
FarmJob JobFromOptions(const FarmOptions& o) {
    if (o.scene.empty()) throw InputError("farm", "", "give a scene (or --status/--assemble DIR)");
    if (o.output.empty())
        throw InputError("--output", "", "give the job's folder, e.g. -o out/farm");
    FarmJob job;
    job.folder = fs::absolute(o.output).lexically_normal().string();
    while (job.folder.size() > 1 && job.folder.back() == '/') job.folder.pop_back();
    CheckFarmPath("--output", job.folder);
    // sbatch reads #SBATCH lines by its own rules (whitespace splits, quotes, # and % mean
    // something), so the folder that appears in them is kept to plain characters.
    for (char c : job.folder)
        if (std::isspace(static_cast<unsigned char>(c)) ||
            std::string("%\"'\\#").find(c) != std::string::npos)
            throw InputError("--output", job.folder,
                             "Slurm's batch scripts cannot name a folder with spaces or any of "
                             "% \" ' \\ #; give another");
    CheckSlurmField("--partition", o.partition);
    CheckSlurmField("--time", o.timeLimit);
    FarmFrames& f = job.frames;
    if (!ParseFrames(o.frames, &f.frames.first, &f.frames.end))
        throw InputError("--frames", o.frames, FramesProblem(o.frames));
    std::string scene = ScenePathFor(o.scene);
    std::error_code ec;
    if (fs::exists(scene, ec)) scene = fs::absolute(scene).lexically_normal().string();
    CheckFarmPath("scene", scene);
    const LoadedScene loaded = LoadSceneFile(scene);  // bad scenes fail here, not on the nodes
    f.scene = scene;
    // Of the scene file and every file it brought in (models, a glTF file's buffers and
    // images): a task finds any of them edited.
    if (const std::vector<std::string> files = AssetFilesRead(); !files.empty())
        f.sceneChecksum = HexDigest(HashFiles(files));
    f.width = loaded.width.value_or(1280);
    f.height = loaded.height.value_or(720);
    if (!o.size.empty()) ParseSize(o.size, &f.width, &f.height);
    f.spp = o.spp;
    f.fps = o.fps;
    f.backend = o.backend.empty() ? (o.gpu ? "cuda" : "cpu") : o.backend;
    f.format = o.format.empty() ? (CanReadImages() ? "png" : "ppm") : o.format;
    if (f.format == "png" && !CanReadImages())
        throw InputError(
            "--format", "png",
            "this rtrt cannot write PNG (built without OpenImageIO); use --format ppm");
    FarmScheduling& s = job.scheduling;
    s.shards = o.shards;
    s.gpu = o.gpu;
    s.partition = o.partition;
    s.timeLimit = o.timeLimit;
    s.cpusPerTask = o.cpusPerTask;
    return job;
}

std::vector<int> FramesToRender(const FrameCheck& check) {
    std::vector<int> frames = check.missing;
    frames.insert(frames.end(), check.corrupt.begin(), check.corrupt.end());
    std::sort(frames.begin(), frames.end());
    return frames;
}

// The tasks run one after another on this machine, then the assembly.
int RunLocally(FarmJob job, const std::vector<std::vector<FrameRange>>& tasks,
               FarmFolderLock& lock) {
    // A back end this machine lacks fails before the folder holds a job of its settings.
    if (Backend backend; job.frames.backend == "cuda") {
        std::string why;
        if (!ChooseBackend("cuda", &backend, &why))
            throw job.scheduling.gpu
                ? InputError("--gpu", "the CUDA back end", why + "; leave out --gpu with --local")
                : InputError("--backend", "cuda", why + "; use --backend cpu with --local");
    }
    // Kept once its folders are there: a full disk at farm.json removes the folder it made.
    try {
        StartJob(job);
    } catch (const OutputError& e) {
        throw OutputError(
            e.File(), e.Reason() + "; nothing was started: rerun this command once that is fixed");
    }
    lock.Keep();
    const std::string manifest =
        ManifestFolder(job.folder) + "/local-" + std::to_string(::getpid()) + ".tsv";
    // A task outlives no farm: killed (even with SIGKILL), the farm takes its task with it, and
    // a rerun does not render the same frames beside an orphan.
    ChildOptions task;
    task.endWithParent = true;
    for (size_t t = 0; t < tasks.size(); ++t)
        for (const FrameRange& range : tasks[t]) {
            std::printf("rtrt farm: task %zu of %zu: frames %s\n", t + 1, tasks.size(),
                        RangeText(range).c_str());
            std::fflush(stdout);
            const int status =
                RunProgram(PlayCommand(job, RtrtPath(), range, manifest), nullptr, task);
            // Bad input: the task's one line has said what is wrong, and a rerun would fail
            // the same way.
            if (status == kExitBadInput) return kExitBadInput;
            if (status != 0) {
                std::fprintf(stderr,
                             "rtrt: error: the task for frames %s failed (exit %d); the frames "
                             "finished are kept, and rerunning the command renders the rest\n",
                             RangeText(range).c_str(), status);
                return kExitFailure;
            }
        }
    AssembleVideo(job);
    std::printf("rtrt farm: %s and %s are ready\n", VideoFile(job.folder).c_str(),
                ContactSheetFile(job.folder).c_str());
    return kExitOk;
}

// FOLDER/slurm/KIND-N.sbatch: the batch script of the job's next submission.
std::string NextScript(const FarmJob& job, const char* kind) {
    return job.folder + "/slurm/" + kind + "-" + std::to_string(job.submissions.size() + 1) +
           ".sbatch";
}

// sbatch exited 0 without a job id: what it took is unknown, so nothing is undone.
struct SubmittedUnknown {
    std::string folder, reason;
};

// Submits a script with sbatch --parsable: the job id. OutputError naming the job's folder when
// sbatch fails, ending with what to do instead (next).
std::string Submit(const std::vector<std::string>& command, const FarmJob& job, const char* what,
                   const std::string& next) {
    std::string output, error;
    const int status = RunProgram(command, &output, {}, &error);
    const std::string id = output.substr(0, output.find_first_of(";\n"));
    if (!error.empty())  // it did not start
        throw OutputError(job.folder, "could not run sbatch (" + error + "); " + next);
    if (status != 0)
        throw OutputError(job.folder, std::string("sbatch refused the ") + what + " (exit " +
                                          std::to_string(status) + "; its message is above); " +
                                          next);
    if (id.empty() || id.find_first_not_of("0123456789") != std::string::npos) {
        // It exited 0, so it may have taken the job: the folder and its scripts stay for it.
        std::string printed = output.substr(0, 200);
        while (!printed.empty() && std::isspace(static_cast<unsigned char>(printed.back())))
            printed.pop_back();
        throw SubmittedUnknown{
            job.folder, std::string("sbatch exited 0 but printed no job id for the ") + what +
                            " (it printed \"" + WithoutControlCharacters(printed) +
                            "\"); it may have been submitted: look for it with squeue --me, "
                            "scancel it or let it run, then rerun this command"};
    }
    return id;
}

// farm.json records what sbatch took; when it cannot be written (a full disk), the error names
// the job ids, which no rerun could otherwise see.
void RecordSubmission(const FarmJob& job) {
    try {
        WriteFarmJob(job);
    } catch (const std::exception& e) {
        const FarmSubmission& s = job.submissions.back();
        std::string ids = s.renderJob;
        if (!s.assembleJob.empty()) ids += (ids.empty() ? "" : " ") + s.assembleJob;
        throw OutputError(job.folder, "Slurm took job " + ids + " (" + SubmissionText(s) +
                                          "), but farm.json could not record it (" + e.what() +
                                          "); scancel " + ids +
                                          ", free some space, and rerun this command");
    }
}

int SubmitToSlurm(FarmJob job, const std::vector<std::vector<FrameRange>>& tasks,
                  FarmFolderLock& lock) {
    const StartedJob started = StartJob(job);
    const std::string renderScript = NextScript(job, "render");
    const std::string assembleScript = NextScript(job, "assemble");
    FarmSubmission& submission = job.submissions.emplace_back();
    // Until sbatch has taken a job (a wrong partition or account, a controller that is down), a
    // refusal leaves the folder as this run found it, so that the corrected command, with other
    // settings too, starts afresh; after that, what was submitted stays recorded.
    try {
        if (!tasks.empty()) {
            WriteWholeFile(renderScript, RenderScript(job, tasks, RtrtPath()), /*durable=*/true);
            submission.renderJob =
                Submit(SubmitRender(renderScript), job, "render array",
                       "nothing was submitted or kept; to render on this machine instead: " +
                           FarmCommandLine(job, " --local"));
            lock.Keep();
            // Recorded at once: --status and the queue check see it even if the assembly fails.
            RecordSubmission(job);
        }
        WriteWholeFile(assembleScript, AssembleScript(job, RtrtPath()), /*durable=*/true);
        submission.assembleJob = Submit(
            SubmitAssembly(assembleScript, submission.renderJob), job, "assembly",
            submission.renderJob.empty()
                ? "every frame is done; to assemble on this machine instead: rtrt farm "
                  "--assemble " +
                      ShellQuote(job.folder)
                : "render job " + submission.renderJob +
                      " is queued and recorded; once it has ended, rerun this command (or rtrt "
                      "farm --assemble " +
                      ShellQuote(job.folder) + ")");
    } catch (const SubmittedUnknown& unknown) {
        // The submission stays recorded, without ids: the folder keeps these settings, and the
        // rerun's queue check has nothing to ask about, as the message says.
        lock.Keep();
        RecordSubmission(job);
        throw OutputError(unknown.folder, unknown.reason);
    } catch (...) {
        if (submission.renderJob.empty())
            UndoStart(started, {renderScript, assembleScript});
        else
            UndoStart({}, {assembleScript});  // the render job is recorded, or the error names it
        throw;
    }
    lock.Keep();
    RecordSubmission(job);
    if (!submission.renderJob.empty())
        std::printf("rtrt farm: submitted render job %s (%zu tasks) and assemble job %s after it\n",
                    submission.renderJob.c_str(), tasks.size(), submission.assembleJob.c_str());
    else
        std::printf("rtrt farm: every frame is done; submitted assemble job %s\n",
                    submission.assembleJob.c_str());
    std::printf("rtrt farm: follow it with: rtrt farm --status %s\n",
                ShellQuote(job.folder).c_str());
    return kExitOk;
}

void PrintDryRun(const FarmJob& job, const std::vector<std::vector<FrameRange>>& tasks) {
    if (!tasks.empty()) {
        const std::string script = NextScript(job, "render");
        std::printf("# %s, submitted as: %s\n%s\n", script.c_str(),
                    ShellLine(SubmitRender(script)).c_str(),
                    RenderScript(job, tasks, RtrtPath()).c_str());
    }
    const std::string script = NextScript(job, "assemble");
    std::printf("# %s, submitted as: %s\n%s", script.c_str(),
                ShellLine(SubmitAssembly(script, tasks.empty() ? "" : "RENDER_JOB_ID")).c_str(),
                AssembleScript(job, RtrtPath()).c_str());
    std::printf("# (dry run: nothing was written or submitted)\n");
}

// Slurm's MaxArraySize (array indices run below it), or 0 when scontrol does not say.
int SlurmMaxArraySize() {
    std::string config;
    ChildOptions quiet;
    quiet.quietStderr = true;
    if (RunProgram({"scontrol", "show", "config"}, &config, quiet) != 0) return 0;
    const size_t at = config.find("MaxArraySize");
    int size = 0;
    if (at == std::string::npos ||
        std::sscanf(config.c_str() + at, "MaxArraySize = %d", &size) != 1)
        return 0;
    return size;
}

int RunFarm(const FarmOptions& o) {
    FarmJob described = JobFromOptions(o);
    if (described.frames.backend == "cuda" && !described.scheduling.gpu && !o.local)
        std::fprintf(stderr,
                     "rtrt farm: warning: --backend cuda without --gpu: the tasks ask Slurm for no "
                     "GPU, so they run only on nodes whose GPUs any job may use; add --gpu to give "
                     "each task one\n");
    // Held until the tasks have run (--local) or been submitted; a dry run writes nothing.
    std::optional<FarmFolderLock> lock;
    if (!o.dryRun) lock.emplace(described.folder);
    bool takenUp = false;
    const FarmJob job = ResumeOrStart(std::move(described), &takenUp);
    if (lock) ReportStaleTemporaries(*lock);
    // Frames of queued tasks are not missing, only unfinished: a second job would render them
    // again and race the first one's assembly.
    if (const SlurmQueueState queue = AskSlurmQueue(job); !o.dryRun) {
        if (!queue.active.empty()) {
            std::fprintf(stderr,
                         "rtrt: error: %s: its Slurm jobs are still queued (%s); follow them with "
                         "rtrt farm --status %s, or scancel them, then rerun this command\n",
                         job.folder.c_str(), queue.active.c_str(), ShellQuote(job.folder).c_str());
            return kExitFailure;
        }
        if (!queue.known && !o.ignoreQueue) {
            std::string jobs;
            for (const FarmSubmission& s : job.submissions)
                jobs += (jobs.empty() ? "" : "; ") + SubmissionText(s);
            std::fprintf(stderr,
                         "rtrt: error: %s: cannot tell whether its Slurm jobs (%s) are still "
                         "queued: %s; rerun this once squeue works, or, when they have surely "
                         "ended (scancel them to be sure), with --ignore-queue\n",
                         job.folder.c_str(), jobs.c_str(), queue.problem.c_str());
            return kExitFailure;
        }
    }
    // A new folder has no manifest: every frame is missing, and there is nothing to report.
    std::error_code ec;
    const bool resumed = fs::is_directory(ManifestFolder(job.folder), ec);
    const FrameCheck check = resumed ? CheckAndReport(job) : CheckFrames(job);
    if (takenUp)
        CheckFrameSizes(job, check.done,
                        "the frames in this folder were made with other settings; give the "
                        "options they were rendered with, or another -o");
    // The assembly's outputs are checked before any frame is rendered for them (a FIFO under the
    // video's name had failed the job only at its end).
    if (!o.dryRun)
        for (const std::string& output : {VideoFile(job.folder), ContactSheetFile(job.folder)})
            CheckOutputPath(output);
    const std::vector<int> frames = FramesToRender(check);
    if (frames.empty() && Assembled(job)) {
        std::printf("rtrt farm: nothing to do: every frame, %s and %s are there\n",
                    VideoFile(job.folder).c_str(), ContactSheetFile(job.folder).c_str());
        return kExitOk;
    }
    // With --local this machine assembles: without ffmpeg every frame had been rendered first.
    if (o.local && !o.dryRun && !ProgramOnPath("ffmpeg"))
        throw OutputError(VideoFile(job.folder),
                          "this machine would assemble it, and ffmpeg is not installed (Debian: "
                          "apt-get install ffmpeg); nothing was rendered: install it and rerun, "
                          "or render on Slurm");
    std::vector<std::vector<FrameRange>> tasks = PlanShards(frames, job.scheduling.shards);
    if (!o.local && ProgramOnPath("scontrol"))
        if (const int most = SlurmMaxArraySize(); most > 0 && tasks.size() > size_t(most)) {
            std::printf(
                "rtrt farm: the cluster takes arrays of at most %d tasks (MaxArraySize): "
                "%d tasks instead of %zu\n",
                most, most, tasks.size());
            tasks = PlanShards(frames, most);
        }
    if (o.dryRun) {
        PrintDryRun(job, tasks);
        return kExitOk;
    }
    if (o.local) return RunLocally(job, tasks, *lock);
    if (!ProgramOnPath("sbatch")) {
        std::fprintf(stderr,
                     "rtrt: error: Slurm is not installed here (no sbatch on PATH), so nothing was "
                     "submitted.\nThe same frames rendered on this machine, one task after "
                     "another:\n  %s\n",
                     FarmCommandLine(job, " --local").c_str());
        return kExitFailure;
    }
    return SubmitToSlurm(job, tasks, *lock);
}

// Why a task would refuse the job's scene now (edited since the job was made, or no longer
// loading), or "".
std::string SceneProblem(const FarmJob& job) {
    try {
        LoadSceneFile(job.frames.scene);
        CheckSceneChecksum(job.frames.scene, job.frames.sceneChecksum);
    } catch (const std::exception& e) {  // InputError, or an image library that failed
        return e.what();
    }
    return "";
}

int RunStatus(const std::string& folder) {
    const FarmJob job = ReadFarmJob(fs::absolute(folder).lexically_normal().string());
    const FarmFrames& f = job.frames;
    std::printf("rtrt farm: %s: %s, frames %s, %ux%u, %u spp, %s back end\n", job.folder.c_str(),
                f.scene.c_str(), RangeText(f.frames).c_str(), f.width, f.height, f.spp,
                f.backend.c_str());
    const FrameCheck check = CheckAndReport(job);
    const SlurmQueueState queue = AskSlurmQueue(job);
    std::string slurm = "nothing submitted";
    if (!job.submissions.empty()) {
        const std::string last = SubmissionText(job.submissions.back());
        slurm = !queue.known ? "cannot tell whether " + last + " still run: " + queue.problem
                : queue.active.empty() ? "no job queued (last: " + last + ")"
                                       : queue.active + " (" + last + ")";
    }
    std::printf("rtrt farm: Slurm: %s\n", slurm.c_str());
    const bool assembled = Assembled(job);
    std::printf("rtrt farm: video: %s\n",
                assembled ? (VideoFile(job.folder) + " and " + ContactSheetFile(job.folder)).c_str()
                          : "not made yet");
    if (check.done.size() == size_t(f.frames.Count()) && assembled) return kExitOk;
    if (!queue.known || !queue.active.empty()) return kExitIncomplete;
    // The next step only where it would go on: another run may work in the folder, and a scene
    // edited since the job was made is refused by every task and by the command.
    if (const std::optional<std::string> holder = FarmFolderHolder(job.folder)) {
        std::printf(
            "rtrt farm: another rtrt farm%s is working in this folder; run --status "
            "again once it has ended\n",
            holder->empty() ? "" : (" (" + *holder + ")").c_str());
        return kExitIncomplete;
    }
    // Every frame done: only the assembly is left, which needs no scene.
    if (check.done.size() == size_t(f.frames.Count())) {
        std::printf("rtrt farm: to finish it: rtrt farm --assemble %s\n",
                    ShellQuote(job.folder).c_str());
        return kExitIncomplete;
    }
    if (const std::string problem = SceneProblem(job); !problem.empty()) {
        std::printf("rtrt farm: the tasks refuse the scene now: %s\n", problem.c_str());
        return kExitIncomplete;
    }
    std::printf("rtrt farm: to finish it: %s\n", FarmCommandLine(job, LocalFlag(job)).c_str());
    return kExitIncomplete;
}

int RunAssemble(const std::string& folder) {
    const FarmJob job = ReadFarmJob(fs::absolute(folder).lexically_normal().string());
    // Not while another run works in the folder; a submitting run holds it briefly, so the
    // assembly job waits for it rather than fail.
    FarmFolderLock lock(job.folder, kAssembleLockWaitSeconds);
    ReportStaleTemporaries(lock);
    lock.Keep();
    const FrameCheck check = CheckAndReport(job);
    if (check.done.size() != size_t(job.frames.frames.Count())) {
        std::fprintf(stderr,
                     "rtrt: error: %s: frames are missing or corrupt, so no video was made; "
                     "if the job's render tasks are still queued or running, the assembly job "
                     "runs after them (rtrt farm --status shows them); else render the frames "
                     "with: %s\n",
                     job.folder.c_str(), FarmCommandLine(job, LocalFlag(job)).c_str());
        return kExitFailure;
    }
    AssembleVideo(job);
    std::printf("rtrt farm: wrote %s and %s\n", VideoFile(job.folder).c_str(),
                ContactSheetFile(job.folder).c_str());
    return kExitOk;
}

}  // namespace

void AddFarmCommand(CLI::App& app, int* exitCode) {
    auto o = std::make_shared<FarmOptions>();
    CLI::App* cmd = app.add_subcommand(
        "farm",
        "Render a frame sequence on a Slurm cluster (a job array, then a job that makes the MP4 "
        "and a contact sheet with ffmpeg); rerun to resume");
    cmd->footer(
        "The job's folder must be on a filesystem every node sees, and rtrt at the same path on "
        "each. Exit status: 0 done (submitted), 1 a failure (Slurm or ffmpeg missing or failing), "
        "2 bad input; --status: 0 complete, 3 not yet.");
    cmd->add_option("scene", o->scene, "Scene file (.json, .gltf, .glb) or a scene name");
    cmd->add_option("--frames", o->frames, "Frames to render: N (0 to N-1) or A:B (A to B-1)");
    cmd->add_option("-o,--output", o->output, "The job's folder (frames, manifest, video)");
    cmd->add_option("--shards", o->shards, "Tasks of the job array")
        ->check(CLI::Range(1, 100000))
        ->capture_default_str();
    cmd->add_option("--size", o->size, "Image size WIDTHxHEIGHT (default: the scene's)");
    cmd->add_option("--spp", o->spp, "Samples per pixel, n x n stratified")
        ->check(CLI::IsMember({1u, 4u, 9u, 16u, 25u, 36u, 49u, 64u}))
        ->capture_default_str();
    cmd->add_option("--fps", o->fps, "Frames per second of scene time and of the video")
        ->check(FiniteRange(1.0, 1000.0))
        ->capture_default_str();
    cmd->add_option("--backend", o->backend,
                    "cpu or cuda for every task (default: cuda with --gpu, else cpu)")
        ->check(CLI::IsMember({"cpu", "cuda"}));
    cmd->add_option("--format", o->format, "Frame files: png (default) or ppm")
        ->check(CLI::IsMember({"png", "ppm"}));
    cmd->add_flag("--gpu", o->gpu, "Each task asks Slurm for one GPU (--gres=gpu:1)");
    cmd->add_option("--partition", o->partition, "Slurm partition for the jobs");
    cmd->add_option("--time", o->timeLimit, "Slurm time limit of each task, e.g. 1:00:00");
    cmd->add_option("--cpus-per-task", o->cpusPerTask, "CPUs each task asks for")
        ->check(CLI::Range(1, 4096))
        ->capture_default_str();
    CLI::Option* dryRun =
        cmd->add_flag("--dry-run", o->dryRun,
                      "Print the batch scripts; write and submit nothing (not with --local)");
    CLI::Option* local =
        cmd->add_flag("--local", o->local, "Run the tasks here, one after another, without Slurm");
    cmd->add_flag("--ignore-queue", o->ignoreQueue,
                  "Go on when squeue cannot say whether the folder's Slurm jobs still run (a "
                  "machine outside the cluster); only once they have surely ended");
    CLI::Option* status =
        cmd->add_option("--status", o->status, "Say what the job in this folder has done");
    CLI::Option* assemble = cmd->add_option(
        "--assemble", o->assemble,
        "Check every frame and make the video and contact sheet (the assembly job)");
    // --status and --assemble take the job from its folder, and a dry run runs nothing: an option
    // of another mode given with them would be ignored, so the two are refused together (exit 2).
    // Checked here rather than with CLI11's excludes(), which lists every pair on every option
    // in --help; the help's groups say it once.
    for (CLI::Option* option : cmd->get_options())
        if (option != status && option != assemble && option != cmd->get_help_ptr())
            option->group("Job options (rtrt farm SCENE ...)");
    status->group("Other modes (each takes only the job's folder)");
    assemble->group("Other modes (each takes only the job's folder)");
    auto refuseOtherModes = [cmd, status, assemble, dryRun, local] {
        for (CLI::Option* mode : {status, assemble, dryRun}) {
            if (mode->count() == 0) continue;
            for (CLI::Option* other : cmd->get_options()) {
                const bool excluded = mode == dryRun ? other == local : other != mode;
                if (excluded && other != cmd->get_help_ptr() && other->count() > 0)
                    throw CLI::ExcludesError(mode->get_name(), other->get_name());
            }
        }
    };
    cmd->callback([o, exitCode, refuseOtherModes] {
        refuseOtherModes();
        if (!o->status.empty())
            *exitCode = RunStatus(o->status);
        else if (!o->assemble.empty())
            *exitCode = RunAssemble(o->assemble);
        else
            *exitCode = RunFarm(*o);
    });
}

}  // namespace rtrt
