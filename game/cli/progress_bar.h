#pragma once
// The one-line progress bar of long commands, drawn on stderr (stdout stays for results).
#include <cstdio>

namespace rtrt {

// "\rrtrt COMMAND: [=====     ] WHAT"; a newline once done == total.
inline void DrawProgressBar(const char* command, int done, int total, const char* what) {
    constexpr int kWidth = 30;
    const int filled = total > 0 ? done * kWidth / total : kWidth;
    std::fprintf(stderr, "\rrtrt %s: [%.*s%*s] %-24s", command, filled,
                 "==============================", kWidth - filled, "", what);
    if (done == total) std::fprintf(stderr, "\n");
    std::fflush(stderr);
}

}  // namespace rtrt
