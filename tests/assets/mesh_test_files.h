#pragma once
// What the mesh loader tests share: a scratch folder per test, gzip and binary PLY writers, the
// sample PLY files, and the checks of an error and of a loaded mesh.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "engine/core/error.h"
#include "game/assets/mesh_io.h"
#include "tests/test_util.h"

namespace rtrt::mesh_test {

// Real models come from tools/fetch_models.sh (tests/test_util.h finds them).
inline std::filesystem::path ModelDir() { return test::ModelDir(); }

inline uint32_t Crc32(std::string_view data) {
    uint32_t crc = 0xFFFFFFFFu;
    for (unsigned char c : data) {
        crc ^= c;
        for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
    return ~crc;
}

inline void AppendLittleEndian(std::string& out, uint64_t value, int bytes) {
    for (int i = 0; i < bytes; ++i) out += static_cast<char>((value >> (8 * i)) & 0xFF);
}

// A gzip member (RFC 1952) holding DATA in stored deflate blocks (RFC 1951): a valid file for
// gzread without linking zlib into the test.
inline std::string Gzip(std::string_view data) {
    std::string out = {'\x1f', '\x8b', 8, 0, 0, 0, 0, 0, 0, 3};
    size_t offset = 0;
    do {
        size_t length = std::min<size_t>(data.size() - offset, 0xFFFF);
        out += static_cast<char>(offset + length == data.size() ? 1 : 0);  // BFINAL, BTYPE 00
        AppendLittleEndian(out, length, 2);
        AppendLittleEndian(out, ~length & 0xFFFF, 2);
        out.append(data.substr(offset, length));
        offset += length;
    } while (offset < data.size());
    AppendLittleEndian(out, Crc32(data), 4);
    AppendLittleEndian(out, data.size() & 0xFFFFFFFFu, 4);
    return out;
}

// Binary PLY data in either byte order.
class Bytes {
  public:
    explicit Bytes(bool bigEndian) : bigEndian_(bigEndian) {}
    template <class T>
    Bytes& Put(T value) {
        char raw[sizeof(T)];
        std::memcpy(raw, &value, sizeof(T));
        for (size_t i = 0; i < sizeof(T); ++i) {
            data_ += raw[bigEndian_ ? sizeof(T) - 1 - i : i];
        }
        return *this;
    }
    const std::string& Data() const { return data_; }

  private:
    bool bigEndian_;
    std::string data_;
};

class MeshIoTest : public ::testing::Test {
  protected:
    void SetUp() override {
        const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = std::filesystem::temp_directory_path() /
               ("rtrt_mesh_io_" + std::to_string(getpid()) + "_" + info->name());
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }

    std::string Write(const std::string& name, std::string_view contents) {
        std::string path = (dir_ / name).string();
        std::ofstream(path, std::ios::binary)
            .write(contents.data(), static_cast<std::streamsize>(contents.size()));
        return path;
    }

    std::filesystem::path dir_;
};

// LoadMesh(path) must throw an InputError naming the file, the field and the reason.
inline void ExpectInputError(const std::string& path, const std::string& field,
                             const std::string& reason) {
    try {
        LoadMesh(path);
        ADD_FAILURE() << "no InputError for " << path << ", expected " << field << ": " << reason;
    } catch (const InputError& error) {
        std::string what = error.what();
        EXPECT_EQ(error.File(), path);
        EXPECT_EQ(error.Field(), field) << what;
        EXPECT_NE(what.find(path), std::string::npos) << what;
        EXPECT_NE(error.Reason().find(reason), std::string::npos) << what;
    }
}

inline void ExpectUnitNormals(const TriangleMesh& mesh) {
    ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
    for (vec3 n : mesh.normals) EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
}

inline void ExpectIndicesInRange(const TriangleMesh& mesh) {
    for (glm::uvec3 t : mesh.indices) {
        EXPECT_LT(t.x, mesh.positions.size());
        EXPECT_LT(t.y, mesh.positions.size());
        EXPECT_LT(t.z, mesh.positions.size());
    }
}

inline const char* const kAsciiPly =
    "ply\n"
    "format ascii 1.0\n"
    "comment written by hand\n"
    "element vertex 5\n"
    "property float x\n"
    "property float y\n"
    "property float z\n"
    "property uchar red\n"
    "property list uchar float extra\n"
    "element edge 1\n"
    "property int vertex1\n"
    "property int vertex2\n"
    "element face 3\n"
    "property uchar flags\n"
    "property list uchar int vertex_indices\n"
    "property float quality\n"
    "end_header\n"
    "0 0 0 255 0\n"
    "1 0 0 255 2 0.5 0.5\n"
    "1 1 0 255 0\n"
    "0 1 0 255 1 7\n"
    "0.25 -0.5 +1.5e1 0 0\n"
    "0 1\n"
    "1 4 0 1 2 3 0.5\n"
    "0 3 0 0 1 1\n"
    "2 3 4 1 0 1\n";

// Four vertices (double x y z between skipped properties of every type), faces first.
inline std::string BinaryPly(bool bigEndian) {
    std::string header = std::string("ply\nformat ") +
                         (bigEndian ? "binary_big_endian" : "binary_little_endian") +
                         " 1.0\n"
                         "element face 2\n"
                         "property list int short vertex_indices\n"
                         "property list uint double weights\n"
                         "element vertex 4\n"
                         "property char a\nproperty uchar b\nproperty short c\n"
                         "property ushort d\nproperty int e\n"
                         "property double x\nproperty double y\nproperty double z\n"
                         "property uint f\nproperty float g\n"
                         "end_header\n";
    Bytes data(bigEndian);
    data.Put<int32_t>(4).Put<int16_t>(0).Put<int16_t>(1).Put<int16_t>(2).Put<int16_t>(3);
    data.Put<uint32_t>(1).Put<double>(1.0);
    data.Put<int32_t>(3).Put<int16_t>(3).Put<int16_t>(3).Put<int16_t>(0);  // degenerate
    data.Put<uint32_t>(0);
    const double xyz[4][3] = {{0, 0, 0}, {1.5, 0, 0}, {1.5, 0.1, -2}, {0, 0.1, -2}};
    for (const auto& p : xyz) {
        data.Put<int8_t>(-1).Put<uint8_t>(2).Put<int16_t>(-3).Put<uint16_t>(4).Put<int32_t>(-5);
        data.Put<double>(p[0]).Put<double>(p[1]).Put<double>(p[2]);
        data.Put<uint32_t>(6).Put<float>(7.0f);
    }
    return header + data.Data();
}

}  // namespace rtrt::mesh_test
