#include "game/farm/slurm_queue.h"

#include <cctype>
#include <map>
#include <vector>

#include "engine/core/child_process.h"

namespace rtrt {

SlurmQueueState AskSlurmQueue(const FarmJob& job) {
    std::vector<std::string> ids;
    for (const FarmSubmission& s : job.submissions)
        for (const std::string& id : {s.renderJob, s.assembleJob})
            if (!id.empty()) ids.push_back(id);
    if (ids.empty()) return {};
    if (!ProgramOnPath("squeue"))
        return {false, "", "squeue is not on PATH here (is this a machine of the cluster?)"};
    // squeue -j with one id the controller has forgotten (MinJobAge after its end) fails with
    // "Invalid job id specified"; with two or more it lists those it knows. The id is given
    // twice, so that a failure means squeue could not ask the controller.
    if (ids.size() == 1) ids.push_back(ids[0]);
    std::string list;
    for (const std::string& id : ids) list += (list.empty() ? "" : ",") + id;
    std::string output;
    const int status = RunProgram({"squeue", "-h", "-r", "-j", list, "-o", "%j %T"}, &output);
    if (status != 0)
        return {false, "",
                "squeue failed (exit " + std::to_string(status) + "; its message is above)"};
    return {true, CountQueueStates(output), ""};
}

std::string CountQueueStates(const std::string& squeueOutput) {
    std::map<std::string, int> states;
    size_t start = 0;
    for (size_t end; (end = squeueOutput.find('\n', start)) != std::string::npos; start = end + 1) {
        const std::string line = squeueOutput.substr(start, end - start);
        // "rtrt-render-NAME RUNNING" counts as "render running".
        const size_t space = line.rfind(' ');
        if (space == std::string::npos) continue;
        std::string state = line.substr(space + 1);
        for (char& c : state) c = char(std::tolower(static_cast<unsigned char>(c)));
        ++states[(line.rfind("rtrt-render", 0) == 0 ? "render " : "assemble ") + state];
    }
    std::string text;
    for (const auto& [state, count] : states)
        text += (text.empty() ? "" : ", ") + std::to_string(count) + " " + state;
    return text;
}

}  // namespace rtrt
