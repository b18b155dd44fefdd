#include "game/gltf/gltf_accessors.h"

#include <algorithm>

#include "game/scene/json_fields.h"

namespace rtrt {

AccessorView GltfAccessor(const GltfDocument& doc, int index, const std::string& field,
                          std::initializer_list<int> types) {
    const tinygltf::Model& model = doc.Model();
    if (index < 0 || size_t(index) >= model.accessors.size())
        doc.Fail(field, "accessor " + std::to_string(index) + " out of range (" +
                            std::to_string(model.accessors.size()) + " accessors)");
    const tinygltf::Accessor& a = model.accessors[size_t(index)];
    const std::string at = JsonIndexed("accessors", size_t(index));
    if (a.sparse.isSparse) throw GltfUnsupported{"sparse accessors are not supported"};
    if (std::find(types.begin(), types.end(), a.type) == types.end())
        doc.Fail(at + ".type", "wrong element type for " + field);
    const int componentBytes = tinygltf::GetComponentSizeInBytes(uint32_t(a.componentType));
    const int components = tinygltf::GetNumComponentsInType(uint32_t(a.type));
    if (componentBytes <= 0 || componentBytes == 8 || components <= 0)
        doc.Fail(at + ".componentType",
                 "unknown component type " + std::to_string(a.componentType));
    if (a.count == 0) doc.Fail(at + ".count", "must be at least 1");
    if (a.bufferView == -1) {
        // No buffer view: every element is zero (glTF 2.0, 5.1.2), e.g. a morph target that
        // moves no normal. One zero element, read again for each (a stride of 0). Its count
        // parallels data the buffers hold (the positions it deltas, say), so that a small file
        // cannot ask for gigabytes of zeros.
        uint64_t bytes = 0;
        for (const tinygltf::Buffer& buffer : model.buffers) bytes += buffer.data.size();
        if (uint64_t(a.count) > bytes / 4)
            doc.Fail(at + ".count", std::to_string(a.count) +
                                        " elements without a buffer view: more than the file's "
                                        "buffers (" +
                                        std::to_string(bytes) +
                                        " bytes) hold of any attribute they could go with");
        static constexpr uint8_t kZeros[64] = {};
        AccessorView v;
        v.data = kZeros;
        v.stride = 0;
        v.count = a.count;
        v.componentType = a.componentType;
        v.components = components;
        v.normalized = a.normalized;
        return v;
    }
    if (a.bufferView < 0 || size_t(a.bufferView) >= model.bufferViews.size())
        doc.Fail(at + ".bufferView",
                 "buffer view " + std::to_string(a.bufferView) + " out of range");
    const tinygltf::BufferView& view = model.bufferViews[size_t(a.bufferView)];
    const std::string viewAt = JsonIndexed("bufferViews", size_t(a.bufferView));
    if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size())
        doc.Fail(viewAt + ".buffer", "buffer " + std::to_string(view.buffer) + " out of range");
    const std::vector<unsigned char>& buffer = model.buffers[size_t(view.buffer)].data;
    if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset)
        doc.Fail(viewAt + ".byteLength", "bytes " + std::to_string(view.byteOffset) + " + " +
                                             std::to_string(view.byteLength) +
                                             " lie outside buffer " + std::to_string(view.buffer) +
                                             " of " + std::to_string(buffer.size()) + " bytes");
    const uint64_t element = uint64_t(componentBytes) * uint64_t(components);
    const uint64_t stride = view.byteStride ? view.byteStride : element;
    if (stride < element || stride > 252)
        doc.Fail(viewAt + ".byteStride", "stride " + std::to_string(stride) +
                                             " does not hold an element of " +
                                             std::to_string(element) + " bytes (or exceeds 252)");
    // count - 1 strides plus one element from byteOffset must fit in the view; count is
    // bounded by the view first, so nothing overflows.
    const uint64_t length = view.byteLength;
    if (a.byteOffset > length || element > length - a.byteOffset ||
        uint64_t(a.count - 1) > (length - a.byteOffset - element) / stride)
        doc.Fail(at + ".count", std::to_string(a.count) + " elements from byte " +
                                    std::to_string(a.byteOffset) + " do not fit in buffer view " +
                                    std::to_string(a.bufferView) + " of " + std::to_string(length) +
                                    " bytes");
    AccessorView v;
    v.data = buffer.data() + view.byteOffset + a.byteOffset;
    v.stride = size_t(stride);
    v.count = a.count;
    v.componentType = a.componentType;
    v.components = components;
    v.normalized = a.normalized;
    return v;
}

}  // namespace rtrt
