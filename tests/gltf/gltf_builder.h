#pragma once
// Small glTF 2.0 files written by the tests themselves, with known answers: a JSON document and
// one binary buffer, saved as .gltf (the buffer as a base64 data URI) or .glb.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace rtrt::test {

class GltfBuilder {
  public:
    using Json = nlohmann::json;

    GltfBuilder() {
        doc["asset"] = {{"version", "2.0"}};
        doc["buffers"] = Json::array();
        doc["bufferViews"] = Json::array();
        doc["accessors"] = Json::array();
    }

    // Appends raw bytes as a buffer view (4-byte aligned) and an accessor over them.
    template <typename T>
    int Accessor(const std::vector<T>& values, int componentType, const char* type,
                 size_t components) {
        while (bin.size() % 4) bin.push_back(0);
        const size_t offset = bin.size();
        bin.resize(offset + values.size() * sizeof(T));
        std::memcpy(bin.data() + offset, values.data(), values.size() * sizeof(T));
        doc["bufferViews"].push_back(
            {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", values.size() * sizeof(T)}});
        doc["accessors"].push_back(
            {{"bufferView", doc["bufferViews"].size() - 1},
             {"componentType", componentType},
             {"count", values.size() * sizeof(T) / (components * ComponentBytes(componentType))},
             {"type", type}});
        return int(doc["accessors"].size() - 1);
    }
    int Floats(const std::vector<float>& v, const char* type, size_t n) {
        return Accessor(v, 5126, type, n);
    }

    // IMAGE's bytes as the file's only image, in a buffer view of its own (4-byte aligned).
    void ImageInBuffer(const std::string& image, const char* mimeType) {
        while (bin.size() % 4) bin.push_back(0);
        doc["bufferViews"].push_back(
            {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", image.size()}});
        bin.insert(bin.end(), image.begin(), image.end());
        doc["images"] =
            Json::array({{{"bufferView", doc["bufferViews"].size() - 1}, {"mimeType", mimeType}}});
    }

    // A mesh of one triangle primitive; returns the mesh index.
    int Mesh(int position, int indices = -1, int uv = -1, int material = -1) {
        Json prim = {{"attributes", {{"POSITION", position}}}};
        if (uv >= 0) prim["attributes"]["TEXCOORD_0"] = uv;
        if (indices >= 0) prim["indices"] = indices;
        if (material >= 0) prim["material"] = material;
        doc["meshes"].push_back({{"primitives", Json::array({prim})}});
        return int(doc["meshes"].size() - 1);
    }

    int Node(Json node) {
        doc["nodes"].push_back(std::move(node));
        return int(doc["nodes"].size() - 1);
    }

    // The document with its buffer embedded as a data URI.
    std::string GltfText() const {
        Json d = doc;
        d["buffers"] =
            Json::array({{{"byteLength", bin.size()},
                          {"uri", "data:application/octet-stream;base64," + Base64(bin)}}});
        return d.dump();
    }

    // The same as a GLB: header, JSON chunk, BIN chunk.
    std::string Glb() const {
        Json d = doc;
        d["buffers"] = Json::array({{{"byteLength", bin.size()}}});
        std::string json = d.dump();
        while (json.size() % 4) json += ' ';
        std::string data(bin.begin(), bin.end());
        while (data.size() % 4) data += '\0';
        std::string out;
        auto u32 = [&](uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); };
        out += "glTF";
        u32(2);
        u32(uint32_t(12 + 8 + json.size() + 8 + data.size()));
        u32(uint32_t(json.size()));
        u32(0x4E4F534Au);
        out += json;
        u32(uint32_t(data.size()));
        u32(0x004E4942u);
        out += data;
        return out;
    }

    static void Save(const std::string& path, const std::string& bytes) {
        std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
    }

    // A 24-bit uncompressed BMP (stb_image reads it), pixels as 0xBBGGRR... given as RGB bytes,
    // row 0 the top of the image.
    static std::string Bmp(int width, int height, const std::vector<uint8_t>& rgb) {
        const int rowBytes = (3 * width + 3) / 4 * 4;
        std::string out;
        auto u16 = [&](uint16_t v) { out.append(reinterpret_cast<const char*>(&v), 2); };
        auto u32 = [&](uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); };
        out += "BM";
        u32(uint32_t(54 + rowBytes * height));
        u32(0);
        u32(54);
        u32(40);
        u32(uint32_t(width));
        u32(uint32_t(height));
        u16(1);
        u16(24);
        u32(0);
        u32(uint32_t(rowBytes * height));
        u32(2835);
        u32(2835);
        u32(0);
        u32(0);
        for (int y = height - 1; y >= 0; --y) {  // BMP rows go bottom-up
            std::string row(size_t(rowBytes), '\0');
            for (int x = 0; x < width; ++x)
                for (int c = 0; c < 3; ++c)
                    row[size_t(3 * x + c)] = char(rgb[size_t(3 * (y * width + x) + (2 - c))]);
            out += row;
        }
        return out;
    }

    // An 8-bit RGBA PNG (stored, not compressed: zlib's stored blocks), row 0 the top.
    static std::string Png(int width, int height, const std::vector<uint8_t>& rgba) {
        std::string raw;
        for (int y = 0; y < height; ++y) {
            raw += '\0';  // filter: none
            raw.append(reinterpret_cast<const char*>(rgba.data()) + size_t(4 * width * y),
                       size_t(4 * width));
        }
        std::string z = "\x78\x01";
        for (size_t at = 0; at < raw.size(); at += 65535) {
            const size_t n = std::min<size_t>(65535, raw.size() - at);
            z += char(at + n == raw.size() ? 1 : 0);
            z += {char(n & 0xff), char(n >> 8), char(~n & 0xff), char((~n >> 8) & 0xff)};
            z += raw.substr(at, n);
        }
        uint32_t a = 1, b = 0;
        for (unsigned char c : raw) a = (a + c) % 65521, b = (b + a) % 65521;
        z += BigEndian((b << 16) | a);
        const std::string header = BigEndian(uint32_t(width)) + BigEndian(uint32_t(height)) +
                                   std::string("\x08\x06\x00\x00\x00", 5);
        return "\x89PNG\r\n\x1a\n" + PngChunk("IHDR", header) + PngChunk("IDAT", z) +
               PngChunk("IEND", "");
    }

    static std::string Base64(const std::vector<uint8_t>& bytes) {
        static const char* kDigits =
            "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
        std::string out;
        for (size_t i = 0; i < bytes.size(); i += 3) {
            const uint32_t n = (uint32_t(bytes[i]) << 16) |
                               (i + 1 < bytes.size() ? uint32_t(bytes[i + 1]) << 8 : 0) |
                               (i + 2 < bytes.size() ? uint32_t(bytes[i + 2]) : 0);
            out += kDigits[(n >> 18) & 63];
            out += kDigits[(n >> 12) & 63];
            out += i + 1 < bytes.size() ? kDigits[(n >> 6) & 63] : '=';
            out += i + 2 < bytes.size() ? kDigits[n & 63] : '=';
        }
        return out;
    }

    Json doc;
    std::vector<uint8_t> bin;

  private:
    static std::string BigEndian(uint32_t v) {
        return {char(v >> 24), char((v >> 16) & 0xff), char((v >> 8) & 0xff), char(v & 0xff)};
    }
    static std::string PngChunk(const char* type, const std::string& data) {
        const std::string body = type + data;
        uint32_t crc = 0xffffffffu;  // CRC-32 of the type and data (PNG's polynomial)
        for (unsigned char c : body) {
            crc ^= c;
            for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
        }
        return BigEndian(uint32_t(data.size())) + body + BigEndian(~crc);
    }
    static size_t ComponentBytes(int componentType) {
        switch (componentType) {
            case 5120:
            case 5121:
                return 1;
            case 5122:
            case 5123:
                return 2;
            default:
                return 4;
        }
    }
};

using Json = nlohmann::json;

// A quad filling [-1, 1]^2 in z = 0, texture coordinate (0, 0) at its top-left corner.
inline int QuadMesh(GltfBuilder& b, int material) {
    const int pos = b.Floats({-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0}, "VEC3", 3);
    const int uv = b.Floats({0, 1, 1, 1, 1, 0, 0, 0}, "VEC2", 2);
    const int idx = b.Accessor(std::vector<uint16_t>{0, 1, 2, 0, 2, 3}, 5123, "SCALAR", 1);
    return b.Mesh(pos, idx, uv, material);
}

// The quad seen by a 90-degree camera from z = 1: it fills the square image exactly. The
// material shows the texture unlit: it is the emissive texture (factor 1) over a black base with
// no specular layer, and the only light shines on the quad's back, so every pixel is its texel.
// The texture is the base colour's too. The caller sets doc["images"][0].
inline GltfBuilder TexturedQuadScene(int filter, int wrap) {
    GltfBuilder b;
    b.doc["samplers"] = Json::array(
        {{{"magFilter", filter}, {"minFilter", filter}, {"wrapS", wrap}, {"wrapT", wrap}}});
    b.doc["textures"] = Json::array({{{"source", 0}, {"sampler", 0}}});
    b.doc["materials"] =
        Json::array({{{"pbrMetallicRoughness",
                       {{"baseColorTexture", {{"index", 0}}},
                        {"baseColorFactor", {0, 0, 0, 1}},
                        {"metallicFactor", 0.0},
                        {"roughnessFactor", 1.0}}},
                      {"emissiveTexture", {{"index", 0}}},
                      {"emissiveFactor", {1, 1, 1}},
                      {"extensions", {{"KHR_materials_specular", {{"specularFactor", 0.0}}}}}}});
    b.doc["cameras"] = Json::array(
        {{{"type", "perspective"},
          {"perspective", {{"yfov", M_PI / 2}, {"aspectRatio", 1.0}, {"znear", 0.01}}}}});
    b.doc["extensions"]["KHR_lights_punctual"]["lights"] =
        Json::array({{{"type", "directional"}, {"color", {1, 1, 1}}}});
    b.doc["extensionsUsed"] = Json::array({"KHR_lights_punctual"});
    const int mesh = QuadMesh(b, 0);
    const int quad = b.Node({{"mesh", mesh}});
    const int camera = b.Node({{"camera", 0}, {"translation", {0, 0, 1}}});
    // Turned half way about y, the light shines along +z, onto the quad's back.
    const int light = b.Node(
        {{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}, {"rotation", {0, 1, 0, 0}}});
    b.doc["scenes"] = Json::array({{{"nodes", {quad, camera, light}}}});
    b.doc["scene"] = 0;
    return b;
}

// The quad facing a 90-degree camera at z = 1, lit from the camera's side by a sun, with a
// dielectric material (base colour 0.6, 0.5, 0.4; roughness 0.4) and IMAGE (a PNG, nearest,
// clamped) as texture 0 in the buffer for the caller's slots.
inline GltfBuilder LitQuadScene(const std::string& image) {
    GltfBuilder b;
    b.doc["samplers"] = Json::array(
        {{{"magFilter", 9728}, {"minFilter", 9728}, {"wrapS", 33071}, {"wrapT", 33071}}});
    b.ImageInBuffer(image, "image/png");
    b.doc["textures"] = Json::array({{{"source", 0}, {"sampler", 0}}});
    b.doc["materials"] = Json::array({{{"pbrMetallicRoughness",
                                        {{"baseColorFactor", {0.6, 0.5, 0.4, 1}},
                                         {"metallicFactor", 0.0},
                                         {"roughnessFactor", 0.4}}}}});
    b.doc["cameras"] = Json::array(
        {{{"type", "perspective"},
          {"perspective", {{"yfov", M_PI / 2}, {"aspectRatio", 1.0}, {"znear", 0.01}}}}});
    b.doc["extensions"]["KHR_lights_punctual"]["lights"] =
        Json::array({{{"type", "directional"}, {"color", {1, 1, 1}}, {"intensity", 3}}});
    b.doc["extensionsUsed"] = Json::array({"KHR_lights_punctual"});
    const int quad = b.Node({{"mesh", QuadMesh(b, 0)}});
    const int camera = b.Node({{"camera", 0}, {"translation", {0, 0, 1}}});
    // Pointing along -z from slightly above: onto the quad's front, the highlight off-centre.
    const int light = b.Node({{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}},
                              {"rotation", {0.1305262, 0, 0, 0.9914449}}});
    b.doc["scenes"] = Json::array({{{"nodes", {quad, camera, light}}}});
    b.doc["scene"] = 0;
    return b;
}

// TexturedQuadScene with the texture as a BMP data URI.
inline std::string TexturedQuadGltf(int texWidth, int texHeight, const std::vector<uint8_t>& rgb,
                                    int filter, int wrap) {
    GltfBuilder b = TexturedQuadScene(filter, wrap);
    const std::string bmp = GltfBuilder::Bmp(texWidth, texHeight, rgb);
    b.doc["images"] =
        Json::array({{{"uri", "data:image/bmp;base64," + GltfBuilder::Base64(std::vector<uint8_t>(
                                                             bmp.begin(), bmp.end()))}}});
    return b.GltfText();
}

// Parent: translate (1, 0, 0), rotate 90 degrees about y; child: translate (0, 0, 2), scale 2.
// The child's mesh point (1, 0, 0) goes to (1, 0, 0) * 2 + (0, 0, 2) = (2, 0, 2) in the parent,
// rotated to (2, 0, -2), moved to (3, 0, -2) in the world.
inline GltfBuilder TwoLevels() {
    GltfBuilder b;
    const int mesh = b.Mesh(b.Floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3));
    const float s = std::sqrt(0.5f);
    b.Node({{"translation", {1, 0, 0}}, {"rotation", {0, s, 0, s}}, {"children", {1}}});
    b.Node({{"translation", {0, 0, 2}}, {"scale", {2, 2, 2}}, {"mesh", mesh}});
    b.doc["scenes"] = Json::array({{{"nodes", {0}}}});
    return b;
}

}  // namespace rtrt::test
