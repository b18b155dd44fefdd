#pragma once
// One farm job: a frame sequence of a scene rendered into an output folder by many tasks
// (Slurm array elements, or local processes), resumable. The folder holds
//   farm.json                 this description, written when the job is first submitted
//   frames/frame_NNNNNN.png   the frames, each written whole (OutputFile)
//   manifest/*.tsv            one per task run: a line per finished frame, with its checksum
//   slurm/                    the batch scripts as submitted; logs/ their output
//   video.mp4, contact_sheet.png   the assembly, made when every frame is there
#include <cstdint>
#include <string>
#include <vector>

namespace rtrt {

// Frames FIRST to END-1.
struct FrameRange {
    int first = 0, end = 0;
    int Count() const { return end - first; }
    bool operator==(const FrameRange&) const = default;
};

// What the frames are: a change of any of these makes other frames, so a folder holds one.
struct FarmFrames {
    std::string scene;          // absolute path of the scene file, or "default"
    std::string sceneChecksum;  // XXH3-64 of the scene file's bytes: an edited scene is another
    FrameRange frames;
    uint32_t width = 0, height = 0;
    uint32_t spp = 1;
    double fps = 60.0;
    // cpu or cuda: one back end for every task (never auto), so that no frame depends on the node
    std::string backend = "cpu";
    std::string format = "png";  // the frames' files: png, or ppm (every build writes it)
    bool operator==(const FarmFrames&) const = default;
};

// How the tasks are scheduled: these may change between submissions of one job.
struct FarmScheduling {
    int shards = 1;
    bool gpu = false;  // each task asks for one GPU (--gres=gpu:1)
    std::string partition, timeLimit;
    int cpusPerTask = 1;
};

// The Slurm jobs of one submission ("" for none: a resubmission with every frame done has no
// render job, and a render job is recorded before its assembly is submitted).
struct FarmSubmission {
    std::string renderJob, assembleJob;
    bool operator==(const FarmSubmission&) const = default;
};
// "render 12 assemble 13", for messages.
std::string SubmissionText(const FarmSubmission& s);

struct FarmJob {
    std::string folder;  // absolute
    FarmFrames frames;
    FarmScheduling scheduling;
    std::vector<FarmSubmission> submissions;  // oldest first
};

// The most bytes farm.json may hold: a job's description is a few hundred bytes, so a FIFO, a
// device or a huge file under its name is refused.
inline constexpr size_t kMaxFarmFileBytes = size_t{1} << 20;

std::string FarmFile(const std::string& folder);      // FOLDER/farm.json
std::string FramesFolder(const std::string& folder);  // FOLDER/frames
std::string FramePattern(const FarmJob& job);         // FOLDER/frames/frame_%06d.png
std::string FrameFile(const FarmJob& job, int frame);
std::string ManifestFolder(const std::string& folder);    // FOLDER/manifest
std::string VideoFile(const std::string& folder);         // FOLDER/video.mp4
std::string ContactSheetFile(const std::string& folder);  // FOLDER/contact_sheet.png

// Reads FOLDER/farm.json; InputError(file, field, reason) when it is missing or malformed.
FarmJob ReadFarmJob(const std::string& folder);
// Writes FOLDER/farm.json whole (OutputError on a failed write).
void WriteFarmJob(const FarmJob& job);
// InputError(option, path, reason) unless farm.json can keep path: JSON text is UTF-8.
void CheckFarmPath(const std::string& option, const std::string& path);
// InputError(what, value, reason) unless value is a Slurm partition name or time limit (letters,
// digits and _-:,.), which the batch scripts and the printed commands may carry unquoted.
void CheckSlurmField(const std::string& what, const std::string& value);

// "" when A and B make the same frames, else what differs, e.g. "size 640x360 there, 320x180 here".
std::string FramesDifference(const FarmFrames& there, const FarmFrames& here);

// InputError naming SCENE unless the files read so far (AssetFilesRead: the scene just loaded and
// what it brought in) have the job's checksum EXPECTED (or the scene file alone does, as jobs
// made before the checksum covered the rest had it); nothing where EXPECTED is empty.
void CheckSceneChecksum(const std::string& scene, const std::string& expected);

// "A:B".
std::string RangeText(const FrameRange& range);
// The frame rate as the command line takes it back exactly ("%.17g": 29.97, 23.976023976023978).
std::string FpsText(double fps);

}  // namespace rtrt
