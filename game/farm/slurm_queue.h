#pragma once
// What Slurm's queue says of a farm job's submissions: whether any is still pending or running,
// or that squeue could not say. A job whose state is unknown is not "nothing queued": a rerun
// would submit the same frames a second time beside the first array and race its assembly.
#include <string>

#include "game/farm/farm_job.h"

namespace rtrt {

struct SlurmQueueState {
    bool known = true;    // false: squeue is missing here or failed
    std::string active;   // "1 render running, 1 assemble pending"; "" when none is queued
    std::string problem;  // why squeue could not say, when not known
};

// Asks squeue about every job id the job's submissions recorded (none recorded: known, none
// queued). squeue's own message, when it fails, goes to standard error.
SlurmQueueState AskSlurmQueue(const FarmJob& job);

// The counts of squeue -h -o "%j %T" lines by kind and state ("2 render running, 1 assemble
// pending").
std::string CountQueueStates(const std::string& squeueOutput);

}  // namespace rtrt
