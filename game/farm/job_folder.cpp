#include "game/farm/job_folder.h"

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "engine/core/content_hash.h"
#include "engine/core/error.h"
#include "engine/core/input_file.h"
#include "engine/core/media_file_check.h"
#include "engine/core/output_file.h"
#include "game/farm/farm_lock.h"
#include "game/farm/frame_size.h"

namespace rtrt {

namespace fs = std::filesystem;

namespace {

// Whether the job's folder holds any work: a frame, a manifest line, the video or the contact
// sheet (temporaries of unfinished writes aside).
bool HoldsWork(const std::string& folder) {
    std::error_code ec;
    for (const std::string& dir : {FramesFolder(folder), ManifestFolder(folder)})
        for (const auto& entry : fs::directory_iterator(dir, ec))
            if (!ParseTemporaryName(entry.path().filename().string()) &&
                !(fs::is_regular_file(entry.path(), ec) && fs::file_size(entry.path(), ec) == 0))
                return true;
    return fs::exists(fs::symlink_status(VideoFile(folder), ec)) ||
           fs::exists(fs::symlink_status(ContactSheetFile(folder), ec));
}

// The scene file's own checksum ("" where it is none), what jobs made before held.
std::string SceneFileChecksum(const std::string& scene) {
    std::error_code ec;
    if (!fs::is_regular_file(scene, ec)) return "";
    try {
        return HexDigest(HashFile(scene));
    } catch (const InputError&) {
        return "";
    }
}

}  // namespace

FarmJob ResumeOrStart(FarmJob job, bool* takenUp) {
    *takenUp = false;
    std::error_code ec;
    // Whatever has farm.json's name is read as the job, so that a folder or a FIFO there is
    // refused for what it is.
    if (fs::exists(fs::symlink_status(FarmFile(job.folder), ec))) {
        FarmJob there = ReadFarmJob(job.folder);
        // A job made before the checksum covered the files a scene brings in holds the scene
        // file's alone: the same scene file is the same job, as it was then.
        if (there.frames.scene == job.frames.scene &&
            there.frames.sceneChecksum != job.frames.sceneChecksum &&
            there.frames.sceneChecksum == SceneFileChecksum(job.frames.scene))
            there.frames.sceneChecksum = job.frames.sceneChecksum;
        const std::string difference = FramesDifference(there.frames, job.frames);
        // A start that never got further (interrupted while sbatch hung) holds nothing the
        // new settings could spoil: they replace its own. A submission, even one whose id is
        // unknown, pins the folder to its settings.
        if (!difference.empty() && there.submissions.empty() && !HoldsWork(job.folder)) return job;
        if (!difference.empty())
            throw InputError(job.folder, "",
                             "holds frames of other settings (" + difference +
                                 "); give another -o, or remove the folder to start again");
        job.submissions = there.submissions;
        return job;
    }
    if (fs::exists(job.folder, ec) && !fs::is_directory(job.folder, ec))
        throw InputError("--output", job.folder, "is a file, not a folder");
    // The farm writes farm.json before its folders (StartJob), so frames/ and manifest/ without
    // it are the tasks' of elsewhere, checked against this job (CheckFrameSizes). The lock and
    // rtrt's temporaries are the farm's own; anything else is refused.
    for (const auto& entry : fs::directory_iterator(job.folder, ec)) {
        const std::string name = entry.path().filename().string();
        // A temporary of some rtrt (".NAME.partialPID-HOST..."): a farm.json whose writer was
        // killed, or the file another run makes and removes at once to see that the folder
        // takes new files (CheckFolderWritable), before it takes the lock.
        const bool temporary = ParseTemporaryName(name).has_value();
        if (name == "frames" || name == "manifest" || name == "logs" || name == "slurm") {
            *takenUp = true;
        } else if (name != kFarmLockName && !temporary) {
            throw InputError(
                "--output", job.folder,
                "holds " + name + " but no farm job (farm.json); give an empty or new folder");
        }
    }
    return job;
}

void CheckFrameSizes(const FarmJob& job, const std::vector<int>& frames,
                     const std::string& advice) {
    const FrameSize want{job.frames.width, job.frames.height};
    for (int frame : frames) {
        const std::string file = FrameFile(job, frame);
        FrameSize size;
        const bool readable = ReadFrameSize(file, &size);
        if (readable && size == want) continue;
        const std::string what =
            readable ? "is " + std::to_string(size.width) + "x" + std::to_string(size.height)
                     : "is no " + job.frames.format + " image";
        throw InputError(file, "",
                         what + ", but the job renders " + std::to_string(want.width) + "x" +
                             std::to_string(want.height) + ": " + advice);
    }
}

StartedJob StartJob(const FarmJob& job) {
    StartedJob started;
    started.folder = job.folder;
    std::error_code ec;
    if (!fs::exists(fs::symlink_status(FarmFile(job.folder), ec)))
        started.made.push_back(FarmFile(job.folder));
    else
        started.before = ReadInputFile(FarmFile(job.folder), kMaxFarmFileBytes);
    WriteFarmJob(job);
    try {
        for (const std::string& dir : {FramesFolder(job.folder), ManifestFolder(job.folder),
                                       job.folder + "/slurm", job.folder + "/logs"}) {
            if (!fs::exists(fs::symlink_status(dir, ec))) started.made.push_back(dir);
            CreateOutputFolder(dir);
        }
    } catch (...) {
        UndoStart(started, {});  // a folder that cannot be made leaves the job as it was
        throw;
    }
    return started;
}

void UndoStart(const StartedJob& started, const std::vector<std::string>& scripts) {
    std::error_code ignored;
    for (const std::string& script : scripts) fs::remove(script, ignored);
    for (auto path = started.made.rbegin(); path != started.made.rend(); ++path)
        fs::remove(*path, ignored);
    if (started.before) {
        try {
            WriteWholeFile(FarmFile(started.folder), *started.before, /*durable=*/true);
        } catch (const std::exception&) {
            // The refusal being reported says more than this would; the job's settings are
            // still readable.
        }
    }
}

bool Assembled(const FarmJob& job) {
    return MediaFileProblem(VideoFile(job.folder)).empty() &&
           MediaFileProblem(ContactSheetFile(job.folder)).empty();
}

}  // namespace rtrt
