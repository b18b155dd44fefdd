#pragma once
// Whether a file that ffmpeg wrote is whole. ffmpeg (5.1) exits 0 when it cannot write an MP4's
// index at the end (a full disk), and a stand-in that exits 0 may write nothing at all: its exit
// status alone would let a file that no player opens take the output's name, and a farm job
// count as assembled.
#include <string>

namespace rtrt {

// "" when PATH holds a whole file of the kinds rtrt has ffmpeg write, told by their first bytes:
// MP4 or QuickTime (boxes that fill the file exactly, a moov and an mdat among them), Matroska (an
// EBML header, then a segment of known size that ends the file) or PNG (chunks that fill the file
// up to its IEND). Else what is wrong, e.g. "is cut short: it has no index (moov box)".
std::string MediaFileProblem(const std::string& path);

}  // namespace rtrt
