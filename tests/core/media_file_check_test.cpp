// Whether a file ffmpeg wrote is whole: MP4 boxes, a Matroska segment, PNG chunks, each whole
// and cut short in the ways a full disk or a failing writer leaves them. (Files ffmpeg really
// wrote pass in the farm's command-line test, whose finished job has nothing left to do.)
#include "engine/core/media_file_check.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdint>
#include <string>

#include "tests/scratch_folder.h"

namespace rtrt {
namespace {

std::string Box(const std::string& type, const std::string& body) {
    const uint32_t size = uint32_t(8 + body.size());
    std::string box = {char(size >> 24), char(size >> 16), char(size >> 8), char(size)};
    return box + type + body;
}

std::string Chunk(const std::string& type, const std::string& data) {
    const uint32_t size = uint32_t(data.size());
    return std::string{char(size >> 24), char(size >> 16), char(size >> 8), char(size)} + type +
           data + std::string(4, '\0');  // the CRC is not checked
}

class MediaFileCheckTest : public test::ScratchFolderTest {
  protected:
    std::string Problem(const std::string& bytes) { return MediaFileProblem(Write("file", bytes)); }
};

TEST_F(MediaFileCheckTest, Mp4BoxesMustFillTheFileWithAnIndexAndMedia) {
    const std::string ftyp = Box("ftyp", std::string("isom\0\0\2\0isomiso2", 16));
    const std::string moov = Box("moov", std::string(40, 'm'));
    const std::string mdat = Box("mdat", std::string(100, 'd'));
    EXPECT_EQ(Problem(ftyp + moov + Box("free", "") + mdat), "");
    EXPECT_EQ(Problem(ftyp + mdat + moov), "");  // the index last, without +faststart
    // ffmpeg 5.1 on a full disk: the media written, the index (written last) lost, exit 0.
    EXPECT_EQ(Problem(ftyp + mdat), "is cut short: it has no index (moov box)");
    EXPECT_EQ(Problem(ftyp + mdat + moov.substr(0, 20)),
              "is cut short: a box goes past the end of the file");
    EXPECT_EQ(Problem(ftyp + moov + mdat.substr(0, 4)), "is cut short inside a box's header");
    EXPECT_EQ(Problem(ftyp + moov), "holds no media data (mdat box)");
    EXPECT_EQ(Problem(ftyp + std::string("\0\0\0\4moov", 8)), "has a box smaller than its header");
    // A last box of size 0 runs to the end of the file.
    EXPECT_EQ(Problem(ftyp + moov + std::string("\0\0\0\0mdat", 8) + "frames"), "");
    EXPECT_EQ(Problem(""), "is empty");
    EXPECT_EQ(Problem("garbage bytes"), "is no MP4, QuickTime, Matroska or PNG file");
}

TEST_F(MediaFileCheckTest, MatroskaSegmentMustBeClosedAndEndTheFile) {
    const std::string header = std::string("\x1A\x45\xDF\xA3\x84", 5) + "webm";
    const std::string segmentId("\x18\x53\x80\x67", 4);
    EXPECT_EQ(Problem(header + segmentId + "\x86" + "clusts"), "");
    // A writer that stopped before closing the segment leaves its size unknown (all ones).
    EXPECT_EQ(Problem(header + segmentId + "\x01\xFF\xFF\xFF\xFF\xFF\xFF\xFF" + "clusters"),
              "is cut short: its segment was never closed (size unknown)");
    EXPECT_EQ(Problem(header + segmentId + "\x88" + "clus"),
              "is cut short: its segment goes past the end");
    EXPECT_EQ(Problem(header + segmentId + "\x82" + "clus"), "holds more than its segment");
    EXPECT_EQ(Problem(header + std::string("\x1F\x43\xB6\x75\x81", 5) + "c"),
              "has no segment after its header");
    EXPECT_EQ(Problem(header.substr(0, 7)), "is cut short inside its headers");
}

TEST_F(MediaFileCheckTest, PngChunksMustEndWithIend) {
    const std::string signature("\x89PNG\r\n\x1a\n", 8);
    const std::string ihdr = Chunk("IHDR", std::string(13, '\1'));
    const std::string idat = Chunk("IDAT", std::string(30, 'z'));
    EXPECT_EQ(Problem(signature + ihdr + idat + Chunk("IEND", "")), "");
    EXPECT_EQ(Problem(signature + ihdr + idat), "is cut short: it has no end (IEND chunk)");
    EXPECT_EQ(Problem(signature + ihdr + idat.substr(0, 20)),
              "is cut short: a chunk goes past the end of the file");
    EXPECT_EQ(Problem(signature + ihdr + Chunk("IEND", "") + "x"),
              "holds bytes after its end (IEND)");
    EXPECT_EQ(MediaFileProblem((dir_ / "missing.png").string()), "cannot be read");
    // A FIFO under a video's name is refused at once (it was waited on for ever).
    ASSERT_EQ(::mkfifo((dir_ / "video.mp4").c_str(), 0600), 0);
    EXPECT_EQ(MediaFileProblem((dir_ / "video.mp4").string()), "is not a regular file");
}

}  // namespace
}  // namespace rtrt
