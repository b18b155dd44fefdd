#include "game/farm/farm_commands.h"

#include <cctype>
#include <cstdio>
#include <filesystem>

namespace rtrt {
namespace {

std::string JobName(const FarmJob& job) {
    std::string name = std::filesystem::path(job.frames.scene).stem().string();
    for (char& c : name)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-') c = '_';
    return name.empty() ? "scene" : name;
}

// The #SBATCH lines both scripts share.
std::string CommonOptions(const FarmJob& job) {
    const FarmScheduling& s = job.scheduling;
    std::string text = "#SBATCH --open-mode=append\n";
    text += "#SBATCH --cpus-per-task=" + std::to_string(s.cpusPerTask) + "\n";
    if (!s.partition.empty()) text += "#SBATCH --partition=" + s.partition + "\n";
    if (!s.timeLimit.empty()) text += "#SBATCH --time=" + s.timeLimit + "\n";
    return text;
}

}  // namespace

std::string ShellQuote(const std::string& text) {
    bool plain = !text.empty();
    for (char c : text)
        plain = plain && (std::isalnum(static_cast<unsigned char>(c)) ||
                          std::string("/._-:=%+,@").find(c) != std::string::npos);
    if (plain) return text;
    std::string quoted = "'";
    for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return quoted + "'";
}

std::string ShellLine(const std::vector<std::string>& words) {
    std::string line;
    for (const std::string& w : words) {
        if (!line.empty())
            line += ' ';  // piecewise: GCC 12 warns falsely (-Wrestrict) on a + chain
        line += ShellQuote(w);
    }
    return line;
}

std::vector<std::string> PlayCommand(const FarmJob& job, const std::string& rtrt,
                                     const FrameRange& range, const std::string& manifest) {
    const FarmFrames& f = job.frames;
    std::vector<std::string> command = {
        rtrt,         "play",
        f.scene,      "--headless",
        "--frames",   RangeText(range),
        "--size",     std::to_string(f.width) + "x" + std::to_string(f.height),
        "--spp",      std::to_string(f.spp),
        "--fps",      FpsText(f.fps),
        "--backend",  f.backend,
        "-o",         FramePattern(job),
        "--manifest", manifest};
    // A scene edited after the job was made fails the task instead of mixing its frames in.
    if (!f.sceneChecksum.empty()) {
        command.push_back("--scene-checksum");
        command.push_back(f.sceneChecksum);
    }
    return command;
}

namespace {

// The #SBATCH lines and the comment of the render array.
std::string RenderHeader(const FarmJob& job, size_t tasks) {
    std::string s = "#!/bin/bash\n";
    s += "#SBATCH --job-name=rtrt-render-" + JobName(job) + "\n";
    s += "#SBATCH --array=0-" + std::to_string(tasks - 1) + "\n";
    s += "#SBATCH --output=" + job.folder + "/logs/render-%A_%a.log\n";
    s += "#SBATCH --requeue\n";
    if (job.scheduling.gpu) s += "#SBATCH --gres=gpu:1\n";
    s += CommonOptions(job);
    s += "# Written by rtrt farm. Array element I renders the frame ranges of case I below, each\n"
         "# frame exactly as a run from frame 0 writes it (rtrt play --frames replays what comes\n"
         "# before), and appends a checksummed line per finished frame to a manifest of its own.\n"
         "# An element that fails for another reason than bad input (exit 2) is requeued, up to " +
         std::to_string(kTaskRequeues) +
         "\n# times; rerunning rtrt farm renders what is still missing.\n";
    return s + "set -u\n";
}

// case "$SLURM_ARRAY_TASK_ID" in I) ranges="A:B C:D" ;; ... esac
std::string RangeTable(const std::vector<std::vector<FrameRange>>& tasks) {
    std::string s = "case \"$SLURM_ARRAY_TASK_ID\" in\n";
    for (size_t i = 0; i < tasks.size(); ++i) {
        std::string ranges;
        for (const FrameRange& r : tasks[i]) {
            if (!ranges.empty()) ranges += ' ';
            ranges += RangeText(r);
        }
        s += "    " + std::to_string(i) + ") ranges=\"" + ranges + "\" ;;\n";
    }
    return s +
           "    *) echo \"rtrt farm: no frames for array element $SLURM_ARRAY_TASK_ID\" >&2; exit "
           "2 "
           ";;\nesac\n";
}

// The play command with the range and the manifest left to the shell's variables, continued
// over lines so that the script reads well where --dry-run prints it.
std::string PlayLine(const FarmJob& job, const std::string& rtrt) {
    const std::vector<std::string> play = PlayCommand(job, rtrt, {}, "");
    std::string line;
    size_t lineStart = 0;
    for (size_t i = 0; i < play.size(); ++i) {
        const std::string option = i > 0 ? play[i - 1] : "";
        const std::string word = option == "--frames"     ? "\"$range\""
                                 : option == "--manifest" ? "\"$manifest\""
                                                          : ShellQuote(play[i]);
        if (i > 0 && word[0] == '-' && line.size() - lineStart + word.size() > 72) {
            line += " \\\n       ";
            lineStart = line.size();
        }
        if (i > 0) line += ' ';
        line += word;
    }
    return line;
}

}  // namespace

std::string RenderScript(const FarmJob& job, const std::vector<std::vector<FrameRange>>& tasks,
                         const std::string& rtrt) {
    std::string s = RenderHeader(job, tasks.size()) + RangeTable(tasks);
    // A node that does not see rtrt (no shared install) would fail every requeue alike.
    s += "[ -x " + ShellQuote(rtrt) + " ] || { echo \"rtrt farm: \"" + ShellQuote(rtrt) +
         "\" is not on $(hostname); install rtrt at the same path on every node\" >&2; exit 2; }\n";
    s += "manifest=" + ShellQuote(ManifestFolder(job.folder) + "/render-") +
         "\"${SLURM_ARRAY_JOB_ID}_${SLURM_ARRAY_TASK_ID}.tsv\"\n";
    // A requeued element goes on after the frames its manifest lists in whole lines (a frame
    // is written before its line): they had all been rendered again. Frames of a range are
    // written in order, so the first one not listed is where the range goes on.
    s += "status=0\nfor range in $ranges; do\n"
         "    if [ -s \"$manifest\" ]; then\n"
         "        first=$(awk -F'\\t' -v f=\"${range%:*}\" 'NF == 4 && length($4) == 16 "
         "{ done[$1] = 1 } END { while (f in done) f++; print f }' \"$manifest\")\n"
         "        [ \"$first\" -ge \"${range#*:}\" ] && continue\n"
         "        range=\"$first:${range#*:}\"\n"
         "    fi\n    " +
         PlayLine(job, rtrt) + " || {\n        status=$?\n        break\n    }\ndone\n";
    s += "if [ \"$status\" -ne 0 ] && [ \"$status\" -ne 2 ] && [ \"${SLURM_RESTART_COUNT:-0}\" "
         "-lt " +
         std::to_string(kTaskRequeues) +
         " ]; then\n"
         "    echo \"rtrt farm: array element $SLURM_ARRAY_TASK_ID failed (exit $status); "
         "requeueing it\"\n"
         "    scontrol requeue \"${SLURM_ARRAY_JOB_ID}_${SLURM_ARRAY_TASK_ID}\"\n"
         "fi\nexit \"$status\"\n";
    return s;
}

std::string AssembleScript(const FarmJob& job, const std::string& rtrt) {
    std::string s = "#!/bin/bash\n";
    s += "#SBATCH --job-name=rtrt-assemble-" + JobName(job) + "\n";
    s += "#SBATCH --output=" + job.folder + "/logs/assemble-%j.log\n";
    s += CommonOptions(job);
    s += "# Written by rtrt farm. Runs once every render task has finished (afterok): checks each\n"
         "# frame against the manifest, then makes video.mp4 and contact_sheet.png with ffmpeg.\n";
    s += "exec " + ShellLine({rtrt, "farm", "--assemble", job.folder}) + "\n";
    return s;
}

std::vector<std::string> SubmitRender(const std::string& script) {
    return {"sbatch", "--parsable", script};
}

std::vector<std::string> SubmitAssembly(const std::string& script, const std::string& renderJob) {
    if (renderJob.empty()) return {"sbatch", "--parsable", script};
    return {"sbatch", "--parsable", "--dependency=afterok:" + renderJob,
            "--kill-on-invalid-dep=yes", script};
}

}  // namespace rtrt
