#pragma once
// Draco-compressed glTF primitives (KHR_draco_mesh_compression), decoded with Debian's libdraco
// before tinygltf reads the file: tinygltf 2.7 knows nothing of the extension and refuses the
// accessors it leaves without a bufferView.
#include <optional>
#include <string>

namespace rtrt {

// Whether this rtrt was built with libdraco.
bool DracoAvailable();

struct DracoDecoded {
    std::string glb;     // the file as a GLB holding the decoded data
    int primitives = 0;  // how many Draco primitives were decoded
};

// Decodes every Draco primitive of a glTF file (BYTES: its whole text, or a GLB when BINARY)
// whose accessors have no uncompressed data: the decoded attributes and indices fill those
// accessors, each primitive becomes a plain triangle list and the extension leaves the document.
// The result is a GLB whose BIN chunk carries the decoded data (after a GLB's own BIN data), so
// that nothing is base64-encoded on the way. DIR resolves external buffers. Throws InputError
// naming the primitive's extension (or the buffer view) and why: no such view, data past its
// buffer, a stream libdraco cannot decode, counts or attributes that do not match the accessors.
// Without libdraco, a file that requires the extension is refused with what to do instead.
// Nothing (no copy, no second parse) for a file whose JSON never names the extension, or when no
// primitive needed decoding.
std::optional<DracoDecoded> DecodeDracoPrimitives(const std::string& file, const std::string& bytes,
                                                  bool binary, const std::string& dir);

}  // namespace rtrt
