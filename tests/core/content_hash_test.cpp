// Content hashes are XXH3-64 (libxxhash): known digests, and streaming equals one shot.
#include "engine/core/content_hash.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <string>

#include "engine/core/error.h"

namespace rtrt {
namespace {

// XXH3_64bits("", 0) with seed 0, as published with xxHash's test vectors.
TEST(ContentHash, EmptyInputHasXxh3Digest) {
    EXPECT_EQ(HashBytes(nullptr, 0), 0x2D06800538D394C2ull);
    EXPECT_EQ(HexDigest(HashBytes(nullptr, 0)), "2d06800538d394c2");
}

TEST(ContentHash, StreamInPiecesEqualsOneShot) {
    std::string data;
    for (int i = 0; i < 5000; ++i) data += char('a' + i * 7 % 26);
    StreamHash stream;
    for (size_t at = 0; at < data.size(); at += 333)
        stream.Update(data.data() + at, std::min<size_t>(333, data.size() - at));
    EXPECT_EQ(stream.Digest(), HashBytes(data.data(), data.size()));
    EXPECT_NE(HashBytes(data.data(), data.size() - 1), HashBytes(data.data(), data.size()));
}

TEST(ContentHash, HexDigestIsSixteenLowercaseDigits) {
    EXPECT_EQ(HexDigest(0), "0000000000000000");
    EXPECT_EQ(HexDigest(0xABCDEF0123456789ull), "abcdef0123456789");
}

// A device would be hashed for ever and a FIFO would block the open: both are refused at once.
TEST(ContentHash, HashFileRefusesWhatIsNotARegularFile) {
    namespace fs = std::filesystem;
    const fs::path dir = fs::temp_directory_path() / "rtrt_content_hash_test";
    fs::remove_all(dir);
    fs::create_directories(dir);
    const std::string fifo = (dir / "pipe").string();
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    for (const std::string& path : {std::string("/dev/zero"), fifo, dir.string()}) {
        try {
            HashFile(path);
            ADD_FAILURE() << path << ": hashed";
        } catch (const InputError& e) {
            EXPECT_EQ(e.File(), path);
            EXPECT_EQ(e.Reason(), "not a regular file") << e.what();
        }
    }
    EXPECT_THROW(HashFile((dir / "missing").string()), InputError);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace rtrt
