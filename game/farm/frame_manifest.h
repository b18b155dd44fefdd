#pragma once
// The manifest of finished frames: text files of one line per frame written,
//   FRAME <tab> FILE NAME <tab> BYTES <tab> XXH3-64 (16 hex digits) <newline>
// appended (and flushed to the disk) only after the frame's file took its name, so a line
// vouches for a whole file. Each task run appends to a file of its own; a line cut short by a
// crash has no newline and is ignored, as is any line that does not parse.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "game/farm/farm_job.h"

namespace rtrt {

struct ManifestEntry {
    int frame = 0;
    std::string file;  // the frame file's name, without its folder
    uint64_t bytes = 0;
    uint64_t hash = 0;
};

// Hashes the finished frame file PATH and appends its line to MANIFEST (OutputError on a failed
// write). `rtrt play --manifest` calls it after each frame.
void AppendToManifest(const std::string& manifest, int frame, const std::string& path);

// Throws InputError("--manifest", PATH, reason) unless PATH can be appended to (or, missing, made
// by the first frame: its folder takes new files),
// so that a bad path fails before any frame is rendered.
void CheckManifestPath(const std::string& path);

// Every entry of every *.tsv in FOLDER, by frame, in the order written (oldest file first).
std::map<int, std::vector<ManifestEntry>> ReadManifests(const std::string& folder);

// What a job's folder holds against what it should.
struct FrameCheck {
    std::vector<int> done;     // a manifest line vouches for the file: its size and checksum
    std::vector<int> missing;  // no manifest line, or no file
    std::vector<int> corrupt;  // a file whose size or checksum is not the manifest's
};
// Checks every frame of JOB (reads and hashes each listed file); PROGRESS, when given, is called
// with the frames checked so far.
FrameCheck CheckFrames(const FarmJob& job, void (*progress)(int done, int total) = nullptr);

// "3-5, 9, 12-40": frames as ranges, for messages.
std::string FramesText(const std::vector<int>& frames, size_t most = 12);

}  // namespace rtrt
