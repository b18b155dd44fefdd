#pragma once
// A video written frame by frame through ffmpeg (H.264 in yuv420p; the container from the file's
// extension: .mp4, .mkv, .mov), as `rtrt play --record out.mp4` records the window. The frames
// are piped to ffmpeg raw; the file takes its name only when ffmpeg has finished it, and an
// interrupt or a failure removes it, so the video is whole or absent.
#include <cstdint>
#include <memory>
#include <string>

#include "engine/core/child_process.h"
#include "engine/core/output_file.h"
#include "engine/render_rt/image.h"

namespace rtrt {

// Whether PATH names a video rtrt records (.mp4, .mkv, .mov), not a folder of frames.
bool IsVideoPath(const std::string& path);

// InputError(--record, PATH, reason) unless ffmpeg is installed and PATH's folder can be
// written: called before a window opens.
void CheckVideoPath(const std::string& path);

// --record PATH checked before a window opens: a video as CheckVideoPath, else a folder for PNG
// frames, which must not be an existing file nor named like a video or image rtrt does not
// record (out.avi had silently become a folder of PNGs), nor a folder holding an earlier
// recording's frames. InputError(--record, PATH, reason).
void CheckRecordPath(const std::string& path);

// The file name of frame N that --record DIR writes: frame_NNNNN.png (more digits past 99999).
std::string RecordedFrameName(int frame);
// Whether NAME (a file name, no folder) is one that RecordedFrameName makes.
bool IsRecordedFrameName(const std::string& name);

class VideoWriter {
  public:
    // A video of WIDTH x HEIGHT at FPS frames per second (odd sizes are padded to even ones).
    VideoWriter(std::string path, uint32_t width, uint32_t height, double fps);
    ~VideoWriter();  // unfinished: ffmpeg's input is closed, it is waited for, the file removed
    VideoWriter(const VideoWriter&) = delete;
    VideoWriter& operator=(const VideoWriter&) = delete;

    // Adds a frame; one of another size (a resized window) is centred, cropped or padded black.
    // OutputError when ffmpeg has stopped.
    void AddFrame(const Image& frame);
    // Ends the video and gives it its name; OutputError when ffmpeg failed.
    void Finish();
    int Frames() const { return frames_; }

  private:
    std::string path_;
    uint32_t width_, height_;
    std::unique_ptr<OutputFile> output_;
    std::unique_ptr<ChildProcess> ffmpeg_;
    int frames_ = 0;
};

}  // namespace rtrt
