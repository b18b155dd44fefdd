#pragma once
// What a farm job's folder holds, and how a run starts in it: a job resumed or new, frames that
// tasks rendered elsewhere taken up, the job's description and folders made (and taken back when
// nothing was submitted), and whether its assembly is there and whole.
#include <optional>
#include <string>
#include <vector>

#include "game/farm/farm_job.h"

namespace rtrt {

// The job as the folder already holds it, or as new; InputError when the folder holds other frames
// or anything that is not a job's. *takenUp: the folder holds frames/ or manifest/ without
// farm.json, from tasks that ran elsewhere (a Kubernetes Indexed Job, README), which this run
// takes up.
FarmJob ResumeOrStart(FarmJob job, bool* takenUp);

// Frames carry no record of their settings (those taken up from tasks that ran elsewhere, or
// written there since): each of FRAMES must at least have this job's size, as one made at another
// would be scaled into the video; else InputError naming the first that has not, ending in ADVICE.
void CheckFrameSizes(const FarmJob& job, const std::vector<int>& frames, const std::string& advice);

// What StartJob changed in a job's folder, for UndoStart.
struct StartedJob {
    std::vector<std::string> made;      // what was not there, in the order made
    std::string folder;                 // the job's
    std::optional<std::string> before;  // farm.json as it was, where there was one
};

// The job's description, then its folders: a farm killed in between leaves farm.json, never
// frames/ or manifest/ without it, which a later run would take for tasks' of elsewhere.
StartedJob StartJob(const FarmJob& job);

// Takes back what StartJob did and the batch scripts that were not submitted, latest first: what
// it made is removed (a folder something has been written into since stays), and farm.json is
// written back as it was (a resubmission with other Slurm options had left them in it).
void UndoStart(const StartedJob& started, const std::vector<std::string>& scripts);

// The video and the contact sheet are there and whole: one that is not (an earlier rtrt kept it
// from an ffmpeg that exited 0 on a full disk) is made again.
bool Assembled(const FarmJob& job);

}  // namespace rtrt
