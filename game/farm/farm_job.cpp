#include "game/farm/farm_job.h"

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "engine/core/content_hash.h"
#include "engine/core/error.h"
#include "engine/core/input_file.h"
#include "engine/core/output_file.h"
#include "game/scene/json_fields.h"

namespace rtrt {

namespace {
// The layout of farm.json this rtrt writes and reads; a newer rtrt may write a higher one.
constexpr int64_t kFarmFileVersion = 1;

void CheckVersion(JsonFields& f) {
    if (!f.Has("version")) f.Fail("version", "missing required field");
    f.ExpectKind("version", JsonKind::kInt);
    const int64_t version = f.Get("version").get<int64_t>();
    const std::string reads = "this rtrt reads version " + std::to_string(kFarmFileVersion);
    if (version > kFarmFileVersion)
        f.Fail("version", "the job was written by a newer rtrt (version " +
                              std::to_string(version) + "; " + reads + ")");
    if (version < kFarmFileVersion)
        f.Fail("version",
               "expected " + std::to_string(kFarmFileVersion) + ", got " + std::to_string(version));
}
}  // namespace

std::string FarmFile(const std::string& folder) { return folder + "/farm.json"; }
std::string FramesFolder(const std::string& folder) { return folder + "/frames"; }
std::string FramePattern(const FarmJob& job) {
    return FramesFolder(job.folder) + "/frame_%06d." + job.frames.format;
}
std::string FrameFile(const FarmJob& job, int frame) {
    char name[64];
    std::snprintf(name, sizeof(name), "/frame_%06d.", frame);
    return FramesFolder(job.folder) + name + job.frames.format;
}
std::string ManifestFolder(const std::string& folder) { return folder + "/manifest"; }
std::string VideoFile(const std::string& folder) { return folder + "/video.mp4"; }
std::string ContactSheetFile(const std::string& folder) { return folder + "/contact_sheet.png"; }

std::string FpsText(double fps) {
    char text[32];
    std::snprintf(text, sizeof(text), "%.17g", fps);
    return text;
}

std::string SubmissionText(const FarmSubmission& s) {
    return "render " + (s.renderJob.empty() ? "-" : s.renderJob) + " assemble " +
           (s.assembleJob.empty() ? "-" : s.assembleJob);
}

std::string RangeText(const FrameRange& range) {
    return std::to_string(range.first) + ":" + std::to_string(range.end);
}

FarmJob ReadFarmJob(const std::string& folder) {
    const std::string file = FarmFile(folder);
    std::error_code ec;
    if (!std::filesystem::exists(file, ec))
        throw InputError(file, "",
                         "cannot be read; is " + folder + " a folder made by `rtrt farm`?");
    // A job's description is a few hundred bytes: a FIFO, a device or a huge file is refused.
    const Json j = ParseJson(ReadInputFile(file, kMaxFarmFileBytes), file);
    if (!j.is_object()) throw InputError(file, "", "expected a JSON object");
    JsonFields f(j, "", file);
    FarmJob job;
    job.folder = folder;
    CheckVersion(f);
    FarmFrames& fr = job.frames;
    fr.scene = f.String("scene");
    fr.sceneChecksum = f.String("scene_checksum", "");
    f.ExpectKind("frames", JsonKind::kInts);
    const Json& frames = f.Get("frames");
    if (frames.size() != 2 || frames[0].get<int64_t>() < 0 ||
        frames[1].get<int64_t>() <= frames[0].get<int64_t>() || frames[1].get<int64_t>() > 1e7)
        f.Fail("frames", "expected [first, end] with 0 <= first < end <= 10000000");
    fr.frames = {int(frames[0].get<int64_t>()), int(frames[1].get<int64_t>())};
    fr.width = f.Count("width", 1, 16384, 0);
    fr.height = f.Count("height", 1, 16384, 0);
    if (fr.width == 0 || fr.height == 0) f.Fail("width", "missing required field");
    fr.spp = f.Count("spp", 1, 64, 1);
    if (f.Has("fps")) {  // a double, as the command line gives it, so that it compares equal
        const Json& fps = f.Get("fps");
        if (!fps.is_number() || !(fps.get<double>() >= 1.0 && fps.get<double>() <= 1000.0))
            f.Fail("fps", "expected a number from 1 to 1000");
        fr.fps = fps.get<double>();
    }
    fr.backend = f.String("backend", "cpu");
    if (fr.backend != "cpu" && fr.backend != "cuda")
        f.Fail("backend", "expected cpu or cuda, got \"" + fr.backend + "\"");
    fr.format = f.String("format", "png");
    if (fr.format != "png" && fr.format != "ppm")
        f.Fail("format", "expected png or ppm, got \"" + fr.format + "\"");
    FarmScheduling& s = job.scheduling;
    s.shards = int(f.Count("shards", 1, 100000, 1));
    f.ExpectKind("gpu", JsonKind::kBool);
    s.gpu = f.Has("gpu") && f.Get("gpu").get<bool>();
    s.partition = f.String("partition", "");
    s.timeLimit = f.String("time_limit", "");
    try {
        CheckSlurmField("partition", s.partition);
        CheckSlurmField("time_limit", s.timeLimit);
    } catch (const InputError& e) {
        f.Fail(e.File(), e.Reason());
    }
    s.cpusPerTask = int(f.Count("cpus_per_task", 1, 4096, 1));
    if (f.Has("submissions")) {
        f.ExpectKind("submissions", JsonKind::kObjects);
        const Json& list = f.Get("submissions");
        for (size_t i = 0; i < list.size(); ++i) {
            JsonFields s(list[i], JsonIndexed("submissions", i), file);
            job.submissions.push_back({s.String("render", ""), s.String("assemble", "")});
            s.Finish();
        }
    }
    f.Finish();
    return job;
}

void WriteFarmJob(const FarmJob& job) {
    const FarmFrames& fr = job.frames;
    const FarmScheduling& s = job.scheduling;
    Json j = {{"version", kFarmFileVersion},
              {"scene", fr.scene},
              {"scene_checksum", fr.sceneChecksum},
              {"frames", {fr.frames.first, fr.frames.end}},
              {"width", fr.width},
              {"height", fr.height},
              {"spp", fr.spp},
              {"fps", fr.fps},
              {"backend", fr.backend},
              {"format", fr.format},
              {"shards", s.shards},
              {"gpu", s.gpu},
              {"partition", s.partition},
              {"time_limit", s.timeLimit},
              {"cpus_per_task", s.cpusPerTask},
              {"submissions", Json::array()}};
    for (const FarmSubmission& s : job.submissions)
        j["submissions"].push_back({{"render", s.renderJob}, {"assemble", s.assembleJob}});
    WriteWholeFile(FarmFile(job.folder), j.dump(2) + "\n", /*durable=*/true);
}

void CheckFarmPath(const std::string& option, const std::string& path) {
    try {
        (void)Json(path).dump();
    } catch (const Json::type_error&) {
        throw InputError(option, path,
                         "is not valid UTF-8, which farm.json cannot keep; rename it");
    }
}

void CheckSlurmField(const std::string& what, const std::string& value) {
    for (char c : value)
        if (!std::isalnum(static_cast<unsigned char>(c)) &&
            std::string("_-:,.").find(c) == std::string::npos)
            throw InputError(what, value, "expected a Slurm name or time, e.g. gpu or 2:00:00");
}

std::string FramesDifference(const FarmFrames& there, const FarmFrames& here) {
    std::vector<std::string> differences;
    auto differ = [&](const std::string& what, const std::string& a, const std::string& b) {
        if (a != b) differences.push_back(what + " " + a + " there, " + b + " here");
    };
    differ("scene", there.scene, here.scene);
    if (there.scene == here.scene && there.sceneChecksum != here.sceneChecksum)
        differences.push_back(
            "the scene or a file it brings in changed since the job started (scene checksum " +
            there.sceneChecksum + " there, " + here.sceneChecksum + " here)");
    differ("frames", RangeText(there.frames), RangeText(here.frames));
    differ("size", std::to_string(there.width) + "x" + std::to_string(there.height),
           std::to_string(here.width) + "x" + std::to_string(here.height));
    differ("spp", std::to_string(there.spp), std::to_string(here.spp));
    differ("fps", FpsText(there.fps), FpsText(here.fps));
    differ("backend", there.backend, here.backend);
    differ("format", there.format, here.format);
    std::string text;
    for (const std::string& d : differences) text += (text.empty() ? "" : "; ") + d;
    return text;
}

// A farm task plays the scene its job was made from, or nothing: frames of an edited scene
// would be mixed into the job's video.
void CheckSceneChecksum(const std::string& scene, const std::string& expected) {
    if (expected.empty()) return;
    const std::string actual = HexDigest(HashFiles(AssetFilesRead()));
    std::error_code ec;
    if (actual == expected ||
        (std::filesystem::is_regular_file(scene, ec) && HexDigest(HashFile(scene)) == expected))
        return;
    throw InputError(scene, "",
                     "changed since its farm job was made, or a file it brings in did (a model, "
                     "a texture; checksum " +
                         actual + ", the job's " + expected +
                         "); restore it, or render the new scene as a new job (another -o)");
}

}  // namespace rtrt
