#pragma once
// A finished frame sequence assembled with ffmpeg (Debian's, with libx264): an H.264 MP4 at the
// job's frame rate and a contact sheet of evenly spaced frames. Each file is written under a
// temporary name and renamed when ffmpeg has succeeded, so it is whole or absent.
#include <vector>

#include "game/farm/farm_job.h"

namespace rtrt {

struct ContactSheetLayout {
    std::vector<int> frames;  // the frames shown, first and last included, in order
    int columns = 0, rows = 0;
    int thumbWidth = 0, thumbHeight = 0;  // even, for the encoders' chroma subsampling
};
// Up to 24 frames, 6 to a row, each at most 320 pixels wide.
ContactSheetLayout PlanContactSheet(const FarmJob& job);

// Writes video.mp4 and contact_sheet.png into the job's folder. OutputError(file, reason) when
// ffmpeg is not installed or fails (its own messages go to standard error).
void AssembleVideo(const FarmJob& job);

}  // namespace rtrt
