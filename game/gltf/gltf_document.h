#pragma once
// A glTF file as tinygltf reads it once the pre-checks (gltf_precheck.h) have passed: the model,
// the file name every message carries, and the warnings given so far. Each part of the import
// (nodes, meshes, materials, animation) reads from it.
#include <tiny_gltf.h>

#include <cmath>
#include <set>
#include <string>
#include <vector>

namespace rtrt {

// A value that is finite and within float's range.
inline bool FiniteFloat(double v) { return std::isfinite(v) && std::fabs(v) <= 3.0e38; }

class GltfDocument {
  public:
    // Reads and checks FILE, then loads it with its buffers and images; throws InputError (file,
    // field, reason) for a malformed file.
    explicit GltfDocument(std::string file);

    const std::string& File() const { return file_; }
    const tinygltf::Model& Model() const { return model_; }

    // "animations[0].channels[N]" of tinygltf's channel c of the first animation: N counts the
    // channels without target.node that tinygltf skipped.
    std::string FirstAnimationChannel(size_t c) const;

    [[noreturn]] void Fail(const std::string& field, const std::string& reason) const;
    // One warning per kind of thing rtrt does not support, however often the file uses it.
    void Warn(const std::string& kind, const std::string& text);

  private:
    std::string file_;
    tinygltf::Model model_;
    std::vector<size_t> firstAnimationChannels_;
    std::set<std::string> warned_;
};

}  // namespace rtrt
