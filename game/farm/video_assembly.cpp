#include "game/farm/video_assembly.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "engine/core/child_process.h"
#include "engine/core/error.h"
#include "engine/core/media_file_check.h"
#include "engine/core/output_file.h"
#include "game/farm/job_folder.h"

namespace rtrt {
namespace {

constexpr int kSheetFrames = 24, kSheetColumns = 6, kThumbWidth = 320;

// Runs ffmpeg to write TARGET: the output's temporary is made (and registered for an interrupt)
// first, ffmpeg writes into it, and it takes TARGET's name only when ffmpeg succeeded.
void RunFfmpeg(std::vector<std::string> arguments, const std::string& target) {
    OutputFile output(target);
    const std::string& temp = output.TemporaryPath();
    std::vector<std::string> argv = {"ffmpeg",    "-nostdin", "-hide_banner",
                                     "-loglevel", "error",    "-y"};
    argv.insert(argv.end(), arguments.begin(), arguments.end());
    argv.push_back("file:" + temp);  // file: so that a name with a colon is no protocol
    std::string error;
    const int status = RunProgram(argv, nullptr, {}, &error);
    if (status != 0)
        throw OutputError(target, "ffmpeg failed (exit " + std::to_string(status) + "; " +
                                      (error.empty() ? "its messages are above" : error) +
                                      "); the frames are kept");
    if (const std::string problem = MediaFileProblem(temp); !problem.empty())
        throw OutputError(target, "ffmpeg exited 0, but the file it wrote " + problem + " (" +
                                      (error.empty() ? "its messages are above" : error) +
                                      "; is the disk full?); the frames are kept");
    output.Finish(/*durable=*/true);
    output.Commit();
}

// An ffconcat list's quoted file name: a quote closes the string, is escaped, and opens it again.
std::string ConcatQuoted(const std::string& path) {
    std::string out = "'";
    for (const char c : path) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

}  // namespace

ContactSheetLayout PlanContactSheet(const FarmJob& job) {
    const FrameRange range = job.frames.frames;
    ContactSheetLayout sheet;
    const int shown = std::min(range.Count(), kSheetFrames);
    for (int k = 0; k < shown; ++k)
        sheet.frames.push_back(
            range.first +
            (shown > 1 ? int(std::lround(double(k) * (range.Count() - 1) / (shown - 1))) : 0));
    sheet.columns = std::min(shown, kSheetColumns);
    sheet.rows = (shown + sheet.columns - 1) / sheet.columns;
    const double aspect = double(job.frames.height) / job.frames.width;
    sheet.thumbWidth = std::max(2, std::min(int(job.frames.width), kThumbWidth) / 2 * 2);
    sheet.thumbHeight = std::max(2, int(std::lround(sheet.thumbWidth * aspect / 2.0)) * 2);
    return sheet;
}

void AssembleVideo(const FarmJob& job) {
    const std::string video = VideoFile(job.folder), sheetFile = ContactSheetFile(job.folder);
    if (!ProgramOnPath("ffmpeg"))
        throw OutputError(video,
                          "ffmpeg is not installed (Debian: apt-get install ffmpeg); the frames "
                          "are kept, and rtrt farm --assemble makes the video once it is");
    if (job.folder.find_first_of("\n\r") != std::string::npos)
        throw InputError(job.folder, "",
                         "ffmpeg's lists cannot name a folder with a line break; move the job "
                         "to another folder");
    // A frame of another size (a task elsewhere of other settings) would be scaled into the video
    // without a word.
    std::vector<int> frames;
    for (int frame = job.frames.frames.first; frame < job.frames.frames.end; ++frame)
        frames.push_back(frame);
    CheckFrameSizes(job, frames,
                    "rendered with other settings? remove it and rerun the job's command to render "
                    "it again");
    const FrameRange range = job.frames.frames;
    // H.264 in yuv420p (what players take) wants even sizes: odd ones get a row or column of
    // padding.
    RunFfmpeg({"-framerate",
               FpsText(job.frames.fps),
               "-start_number",
               std::to_string(range.first),
               "-pattern_type",  // a folder name with [ or * is no glob
               "sequence",
               "-i",
               "file:" + FramePattern(job),
               "-frames:v",
               std::to_string(range.Count()),
               "-vf",
               "pad=ceil(iw/2)*2:ceil(ih/2)*2",
               "-c:v",
               "libx264",
               "-preset",
               "medium",
               "-crf",
               "18",
               "-pix_fmt",
               "yuv420p",
               "-movflags",
               "+faststart"},
              video);

    const ContactSheetLayout sheet = PlanContactSheet(job);
    const std::string listFile = job.folder + "/contact_sheet.ffconcat";
    OutputFile list(listFile);  // never committed: removed after
    std::string text = "ffconcat version 1.0\n";
    // Absolute file: entries: ffmpeg resolves a relative one against the list's path as a URL,
    // where a '?' in the job's folder starts a query (and the frames were looked up elsewhere).
    for (int frame : sheet.frames)
        text += "file " + ConcatQuoted("file:" + FrameFile(job, frame)) + "\n";
    list.Write(text.data(), text.size());
    list.Finish(/*durable=*/false);
    RunFfmpeg({"-f", "concat", "-safe", "0", "-i", "file:" + list.TemporaryPath(), "-vf",
               "scale=" + std::to_string(sheet.thumbWidth) + ":" +
                   std::to_string(sheet.thumbHeight) + ",tile=" + std::to_string(sheet.columns) +
                   "x" + std::to_string(sheet.rows) + ":padding=4:margin=4:color=0x202020",
               "-frames:v", "1", "-update", "1"},
              sheetFile);
}

}  // namespace rtrt
