#pragma once
// The command lines of a farm job: the `rtrt play` of a task, the Slurm batch scripts of the
// render array and of the assembly after it, and the sbatch calls that submit them.
#include <string>
#include <vector>

#include "game/farm/farm_job.h"

namespace rtrt {

// TEXT as one word of a POSIX shell ('...', with ' written as '\'').
std::string ShellQuote(const std::string& text);
std::string ShellLine(const std::vector<std::string>& words);

// `RTRT play SCENE --headless --frames A:B ... --manifest MANIFEST`: one range of a task.
std::vector<std::string> PlayCommand(const FarmJob& job, const std::string& rtrt,
                                     const FrameRange& range, const std::string& manifest);

// The batch script of the render array: element I renders TASKS[I]'s ranges, appends to a
// manifest of its own, and requeues itself when it fails for another reason than bad input.
std::string RenderScript(const FarmJob& job, const std::vector<std::vector<FrameRange>>& tasks,
                         const std::string& rtrt);

// The batch script of the assembly: `RTRT farm --assemble FOLDER`.
std::string AssembleScript(const FarmJob& job, const std::string& rtrt);

// sbatch --parsable SCRIPT, and the assembly's after the render job RENDER_JOB (none: at once).
std::vector<std::string> SubmitRender(const std::string& script);
std::vector<std::string> SubmitAssembly(const std::string& script, const std::string& renderJob);

// How many times a failed task goes back in the queue.
inline constexpr int kTaskRequeues = 3;

}  // namespace rtrt
