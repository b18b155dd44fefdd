#include "game/assets/video_writer.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "engine/core/error.h"
#include "engine/core/media_file_check.h"
#include "engine/core/output_file.h"
#include "game/assets/image_io.h"

namespace rtrt {

bool IsVideoPath(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    return ext == ".mp4" || ext == ".mkv" || ext == ".mov";
}

void CheckVideoPath(const std::string& path) {
    if (!ProgramOnPath("ffmpeg"))
        throw InputError("--record", path,
                         "recording a video needs ffmpeg (Debian: apt-get install ffmpeg); "
                         "or give a folder for PNG frames");
    try {
        CheckOutputPath(path);
    } catch (const InputError& e) {
        throw InputError("--record", path, e.Reason());
    }
}

void CheckRecordPath(const std::string& path) {
    if (IsVideoPath(path)) return CheckVideoPath(path);
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    for (const char* media : {".avi", ".webm", ".gif", ".wmv", ".flv", ".m4v", ".mpg", ".mpeg",
                              ".ts", ".ogv", ".png", ".jpg", ".jpeg", ".exr", ".ppm", ".pfm"})
        if (ext == media)
            throw InputError("--record", path,
                             "rtrt records .mp4, .mkv or .mov video, or PNG frames into a folder; "
                             "give one of those (a " +
                                 ext + " name would have become a folder)");
    std::error_code ec;
    if (std::filesystem::exists(path, ec) && !std::filesystem::is_directory(path, ec))
        throw InputError("--record", path,
                         "is a file; give a video (.mp4, .mkv, .mov) or a folder for PNG frames");
    // Frames of an earlier recording there would mix with this one's (a shorter recording left
    // the rest of the older one after its last frame).
    for (const auto& entry : std::filesystem::directory_iterator(path, ec)) {
        const std::string name = entry.path().filename().string();
        if (IsRecordedFrameName(name))
            throw InputError("--record", path,
                             "holds frames of an earlier recording (" + name +
                                 "): remove them or give another folder");
    }
}

std::string RecordedFrameName(int frame) {
    char name[32];
    std::snprintf(name, sizeof(name), "frame_%05d.png", frame);
    return name;
}

bool IsRecordedFrameName(const std::string& name) {
    const size_t digits = name.size() - std::min(name.size(), sizeof("frame_.png") - 1);
    return digits >= 5 && name.starts_with("frame_") && name.ends_with(".png") &&
           name.find_first_not_of("0123456789", 6) == 6 + digits;
}

VideoWriter::VideoWriter(std::string path, uint32_t width, uint32_t height, double fps)
    : path_(std::move(path)), width_(width), height_(height) {
    output_ = std::make_unique<OutputFile>(path_);  // made and registered for an interrupt
    const std::string& temp = output_->TemporaryPath();
    char rate[32];
    std::snprintf(rate, sizeof(rate), "%.17g", fps);
    ChildOptions o;
    o.pipeStdin = true;
    ffmpeg_ = std::make_unique<ChildProcess>(
        std::vector<std::string>{
            "ffmpeg",     "-nostdin",    "-hide_banner",
            "-loglevel",  "error",       "-y",
            "-f",         "rawvideo",    "-pix_fmt",
            "rgb24",      "-s",          std::to_string(width) + "x" + std::to_string(height),
            "-framerate", rate,          "-i",
            "pipe:0",     "-vf",         "pad=ceil(iw/2)*2:ceil(ih/2)*2",
            "-c:v",       "libx264",     "-preset",
            "veryfast",   "-crf",        "18",
            "-pix_fmt",   "yuv420p",     "-movflags",
            "+faststart", "file:" + temp},  // file: so that a name with a colon is no protocol
        o);
    if (!ffmpeg_->Started()) throw OutputError(path_, "cannot run ffmpeg: " + ffmpeg_->Error());
}

VideoWriter::~VideoWriter() {
    if (ffmpeg_) {
        ffmpeg_->CloseInput();
        ffmpeg_->Wait();
    }
}

void VideoWriter::AddFrame(const Image& frame) {
    const std::vector<uint8_t> bytes = EightBit(CentredOn(frame, width_, height_));
    if (!ffmpeg_->WriteInput(bytes.data(), bytes.size()))
        throw OutputError(path_, "ffmpeg stopped taking frames (exit " +
                                     std::to_string(ffmpeg_->Wait()) + "; its messages are above)");
    ++frames_;
}

void VideoWriter::Finish() {
    ffmpeg_->CloseInput();
    const int status = ffmpeg_->Wait();
    if (status != 0)
        throw OutputError(
            path_, "ffmpeg failed (exit " + std::to_string(status) + "; its messages are above)");
    if (const std::string problem = MediaFileProblem(output_->TemporaryPath()); !problem.empty())
        throw OutputError(path_, "ffmpeg exited 0, but the video it wrote " + problem +
                                     " (its messages are above; is the disk full?)");
    output_->Finish(/*durable=*/true);
    output_->Commit();
}

}  // namespace rtrt
