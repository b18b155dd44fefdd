#pragma once
// The one-line progress bar of long commands, drawn on stderr (stdout stays for results).
#include <unistd.h>

#include <cstdio>

namespace rtrt {

// On a terminal "\rrtrt COMMAND: [=====     ] DONE/TOTAL WHAT", redrawn, with a newline once done
// == total. Into a log or a pipe, no carriage returns: a line "rtrt COMMAND: DONE/TOTAL WHAT" for
// each tenth of the work, and the last.
inline void DrawProgressBar(const char* command, int done, int total, const char* what) {
    if (!isatty(fileno(stderr))) {
        const int step = total >= 10 ? total / 10 : 1;
        if (done % step == 0 || done == total)
            std::fprintf(stderr, "rtrt %s: %d/%d %s\n", command, done, total, what);
        return;
    }
    constexpr int kWidth = 30;
    const int filled = total > 0 ? done * kWidth / total : kWidth;
    std::fprintf(stderr, "\rrtrt %s: [%.*s%*s] %d/%d %-24s", command, filled,
                 "==============================", kWidth - filled, "", done, total, what);
    if (done == total) std::fprintf(stderr, "\n");
    std::fflush(stderr);
}

}  // namespace rtrt
