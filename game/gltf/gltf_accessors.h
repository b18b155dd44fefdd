#pragma once
// glTF accessors: typed views of buffer data, checked to lie inside their
// buffers before anything is read.
#include <cstdint>
#include <cstring>
#include <glm/glm.hpp>
#include <initializer_list>
#include <string>
#include <vector>

#include "game/gltf/gltf_document.h"

namespace rtrt {

// An accessor whose every element lies inside its buffer, read as floats (normalised integers
// scaled as the spec says) or as unsigned indices.
struct AccessorView {
    const uint8_t* data = nullptr;
    size_t stride = 0, count = 0;
    int componentType = 0, components = 0;
    bool normalized = false;

    float Component(size_t element, int c) const {
        const uint8_t* p = data + element * stride;
        switch (componentType) {
            case TINYGLTF_COMPONENT_TYPE_FLOAT: {
                float v;
                std::memcpy(&v, p + 4 * c, 4);
                return v;
            }
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
                return normalized ? p[c] / 255.0f : float(p[c]);
            case TINYGLTF_COMPONENT_TYPE_BYTE: {
                const float v = float(int8_t(p[c]));
                return normalized ? std::max(v / 127.0f, -1.0f) : v;
            }
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
                uint16_t v;
                std::memcpy(&v, p + 2 * c, 2);
                return normalized ? v / 65535.0f : float(v);
            }
            case TINYGLTF_COMPONENT_TYPE_SHORT: {
                int16_t v;
                std::memcpy(&v, p + 2 * c, 2);
                return normalized ? std::max(v / 32767.0f, -1.0f) : float(v);
            }
            default: {
                uint32_t v;
                std::memcpy(&v, p + 4 * c, 4);
                return float(v);
            }
        }
    }
    uint32_t Index(size_t element) const {
        const uint8_t* p = data + element * stride;
        if (componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) return p[0];
        if (componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
            uint16_t v;
            std::memcpy(&v, p, 2);
            return v;
        }
        uint32_t v;
        std::memcpy(&v, p, 4);
        return v;
    }
};

// Thrown for content rtrt skips with a warning (a sparse accessor): the caller drops what used it.
struct GltfUnsupported {
    std::string what;
};

// Accessor INDEX, which FIELD names, of one of the element TYPES (TINYGLTF_TYPE_...). Throws
// GltfUnsupported for a sparse accessor, InputError for one that does not fit its buffer.
AccessorView GltfAccessor(const GltfDocument& doc, int index, const std::string& field,
                          std::initializer_list<int> types);

// The accessor's elements as N floats each; a NaN or infinite element is an InputError.
template <int N>
std::vector<glm::vec<N, float>> ReadGltfFloats(const GltfDocument& doc, int index,
                                               const std::string& field, int type) {
    const AccessorView a = GltfAccessor(doc, index, field, {type});
    std::vector<glm::vec<N, float>> values(a.count);
    for (size_t i = 0; i < a.count; ++i)
        for (int c = 0; c < N; ++c) {
            const float v = a.Component(i, c);
            if (!FiniteFloat(v))
                doc.Fail(field, "accessor " + std::to_string(index) + ", element " +
                                    std::to_string(i) + ": NaN or infinite");
            values[i][c] = v;
        }
    return values;
}

}  // namespace rtrt
