#pragma once
// What rtrt checks of a glTF file before tinygltf reads it: the GLB container, the JSON types of
// the fields rtrt reads (tinygltf drops a mistyped field silently), the fields glTF requires
// (gltf_required_fields.h) and that referenced buffer
// and image files exist, so that each defect gets a message naming its field.
#include <string>
#include <vector>

namespace rtrt {

struct GltfFileBytes {
    std::string bytes;  // the whole file
    bool binary;        // GLB (by extension or magic) rather than JSON text
    // Per image: whether a texture's own `source` names it, so rtrt may sample it. The others
    // (unused, or only an extension's source, as KHR_texture_basisu's KTX2) are not decoded.
    std::vector<bool> imageUsed;
    // The index in the file of each channel of the first animation that names its target.node,
    // in order: tinygltf keeps only those, so its channel c is the file's channel
    // firstAnimationChannels[c].
    std::vector<size_t> firstAnimationChannels;
};

// Reads FILE and checks it as above; throws InputError naming the file and field.
GltfFileBytes ReadCheckedGltf(const std::string& file);

// A glTF URI's path: percent-encoded (RFC 3986), so "a%20b.bin" names "a b.bin".
std::string DecodeGltfUri(const std::string& uri);

}  // namespace rtrt
