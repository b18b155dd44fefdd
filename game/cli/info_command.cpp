// `rtrt info FILE`: what a mesh, an .rtmodel, a scene file or a glTF file holds — counts, bounds,
// materials, lights, animation, and the statistics of every BVH.
#include <cctype>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "engine/core/content_hash.h"
#include "engine/core/error.h"
#include "game/assets/model_cache.h"
#include "game/cli/commands.h"
#include "game/gltf/gltf_import.h"
#include "game/scene/scene_file.h"

namespace rtrt {
namespace {

// 1234567 -> "1,234,567".
std::string Grouped(uint64_t n) {
    std::string digits = std::to_string(n), out;
    for (size_t i = 0; i < digits.size(); ++i) {
        if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
        out += digits[i];
    }
    return out;
}

std::string Vec(vec3 v) {
    char text[96];
    std::snprintf(text, sizeof(text), "(%g, %g, %g)", v.x, v.y, v.z);
    return text;
}

std::string Megabytes(size_t bytes) {
    char text[32];
    std::snprintf(text, sizeof(text), "%.1f MB", double(bytes) / 1e6);
    return text;
}

void PrintBounds(const char* indent, const Aabb& b) {
    std::printf("%sbounds        %s to %s, size %s\n", indent, Vec(b.min).c_str(),
                Vec(b.max).c_str(), Vec(b.Extent()).c_str());
}

void PrintBvh(const char* indent, const Blas& blas) {
    const BvhStats s = ComputeStats(blas.nodes);
    std::printf("%sBVH           SAH cost %.2f, depth %u, %s nodes (%s leaves)\n", indent,
                s.sahCost, s.maxDepth, Grouped(s.nodeCount).c_str(), Grouped(s.leafCount).c_str());
    std::printf("%sleaf sizes    min %u, mean %.2f, max %u; leaves by size:", indent, s.minLeafSize,
                s.meanLeafSize, s.maxLeafSize);
    for (size_t n = 0; n < s.leafSizeHistogram.size(); ++n)
        if (s.leafSizeHistogram[n] > 0)
            std::printf(" %zu:%s", n, Grouped(s.leafSizeHistogram[n]).c_str());
    std::printf("\n%sbytes         %s (binary nodes %s, 4-wide nodes %s, primitives %s)\n", indent,
                Megabytes(blas.Bytes()).c_str(),
                Megabytes(blas.nodes.size() * sizeof(BvhNode)).c_str(),
                Megabytes(blas.nodes4.size() * sizeof(Bvh4Node)).c_str(),
                Megabytes(blas.Bytes() - blas.nodes.size() * sizeof(BvhNode) -
                          blas.nodes4.size() * sizeof(Bvh4Node))
                    .c_str());
}

void PrintModel(const std::string& path) {
    const MeshModel model = LoadMeshModel(path, BvhBuildOptions{});
    const Blas& blas = model.blas;
    const bool rtmodel = model.origin == MeshModel::Origin::kRtModelFile;
    std::printf("%s: %s\n", path.c_str(),
                rtmodel ? ".rtmodel (BLAS stored in the tracer's layout)" : "triangle mesh");
    std::printf("  triangles     %s", Grouped(blas.SourcePrimCount()).c_str());
    if (blas.PrimCount() != blas.SourcePrimCount())
        std::printf(" in %s leaf slots (spatial splits put some in several leaves)",
                    Grouped(blas.PrimCount()).c_str());
    std::printf("\n");
    std::printf("  vertices      %s in the source mesh\n",
                Grouped(model.info.sourceVertexCount).c_str());
    PrintBounds("  ", blas.bounds);
    std::printf("  normals       %s\n",
                blas.normals.empty() ? "none (flat shading)" : "per vertex (smooth shading)");
    std::printf("  colours       %s\n",
                blas.colors.empty() ? "none" : "per vertex (multiply the material's colour)");
    std::printf("  materials     none (a model takes its material from the scene)\n");
    PrintBvh("  ", blas);
    if (rtmodel) {
        const RtModelKey& k = model.info.key;
        std::printf("  format        version %u, revision %u, %s bytes, read in %.1f ms\n",
                    model.info.version, k.revision, Grouped(model.info.fileBytes).c_str(),
                    model.readMs);
        // Only the binned builders (binned, sbvh) use bins; centroid splits at the middle.
        const bool binned =
            k.builder == BvhBuilder::kBinnedSah || k.builder == BvhBuilder::kSpatialSah;
        std::printf("  built by      %s builder (leaves up to %u%s) from a source of hash %s\n",
                    std::string(BuilderName(k.builder)).c_str(), k.maxLeafSize,
                    binned ? (", " + std::to_string(k.binCount) + " bins").c_str() : "",
                    HexDigest(k.sourceHash).c_str());
    } else if (model.origin == MeshModel::Origin::kCache) {
        std::printf("  BVH source    cache %s (read in %.1f ms)\n", model.cachePath.c_str(),
                    model.readMs);
    } else {
        std::printf("  BVH source    built now: parse %.1f ms, build %.1f ms%s%s\n", model.parseMs,
                    model.buildMs, model.cachePath.empty() ? "" : "; cached as ",
                    model.cachePath.c_str());
    }
}

void PrintScene(const std::string& path) {
    const LoadedScene loaded = LoadSceneFile(path);
    const RenderScene& scene = loaded.scene;
    std::printf("%s: %s\n", path.c_str(), IsGltfPath(path) ? "glTF 2.0 scene" : "scene file");
    for (const GltfSummary& g : loaded.gltfFiles) {
        std::printf("  glTF          %s\n", g.file.c_str());
        std::printf("    nodes       %u in the scene shown; %u meshes, %u triangle primitives\n",
                    g.nodes, g.meshes, g.primitives);
        std::printf("    geometry    %s triangles, %s vertices\n", Grouped(g.triangles).c_str(),
                    Grouped(g.vertices).c_str());
        std::printf("    materials   %u, textures %u\n", g.materials, g.textures);
        std::printf("    cameras     %u placed, lights %u placed\n", g.cameras, g.lights);
        std::printf("    deforming   %u skins; %u skinned or morphed primitives\n", g.skins,
                    g.deformingPrimitives);
        std::printf("    animations  %u", g.animations);
        if (g.animations > 0)
            std::printf(" (the first plays: %u nodes, %.3g s, looping)", g.animatedNodes,
                        g.animationSeconds);
        std::printf("\n");
    }
    std::printf("  camera        at %s looking along %s, vertical field of view %g degrees%s\n",
                Vec(scene.camera.position).c_str(), Vec(scene.camera.forward).c_str(),
                scene.camera.fovYDegrees,
                loaded.cameraPath.empty()
                    ? ""
                    : (", path of " + std::to_string(loaded.cameraPath.size()) + " keys").c_str());
    std::printf("  image         %ux%u, max depth %u\n", loaded.width.value_or(1280),
                loaded.height.value_or(720), scene.maxDepth);
    std::printf("  materials     %zu:", scene.materials.size());
    for (size_t i = 0; i < scene.materials.size(); ++i)
        std::printf(" %s", i < loaded.materialNames.size() ? loaded.materialNames[i].c_str()
                                                           : "(default grey)");
    std::printf("\n  lights        %zu\n", scene.lights.size());
    for (const Light& l : scene.lights) {
        const char* kind = l.type == LightType::kDirectional ? "directional toward"
                           : l.type == LightType::kPoint     ? "point at"
                                                             : "spot at";
        std::printf("                %s %s, colour %s", kind, Vec(l.vector).c_str(),
                    Vec(l.color).c_str());
        if (l.type == LightType::kSpot) std::printf(", shining along %s", Vec(l.spotAxis).c_str());
        if (l.falloff) {
            std::printf(", inverse-square falloff");
            if (l.range > 0.0f) std::printf(" to range %g", l.range);
        }
        std::printf("\n");
    }
    size_t animated = 0, bodies = 0, later = 0;
    for (const EntityDesc& e : loaded.entities) {
        animated += e.animator.has_value();
        bodies += e.body.has_value();
        later += e.spawnTime > 0.0f;
    }
    std::printf(
        "  instances     %s at time 0 (%s entities: %zu animated, %zu rigid bodies, %zu "
        "spawned later); %s triangles over all instances\n",
        Grouped(scene.instances.size()).c_str(), Grouped(loaded.entities.size()).c_str(), animated,
        bodies, later, Grouped(scene.TriangleCount()).c_str());
    std::printf("  models        %zu\n", scene.blases.size());
    for (size_t i = 0; i < scene.blases.size(); ++i) {
        const Blas& blas = *scene.blases[i];
        std::printf("  - %s: %s %s\n",
                    i < loaded.modelNames.size() ? loaded.modelNames[i].c_str() : "?",
                    Grouped(blas.SourcePrimCount()).c_str(),
                    blas.kind == GeometryKind::kSpheres ? "spheres" : "triangles");
        PrintBounds("    ", blas.bounds);
        PrintBvh("    ", blas);
    }
}

void RunInfo(const std::string& argument) {
    if (argument.empty())
        throw InputError("info", "file", "give a mesh, an .rtmodel, a scene or a glTF file");
    // A bare name (demo_physics, default) is one of the project's scenes, as render and play
    // take it.
    const std::string path = ScenePathFor(argument);
    std::error_code ec;
    if (path == "default" && !std::filesystem::exists(path, ec)) return PrintScene(path);
    if (!std::filesystem::exists(path, ec))
        throw InputError(path, "", "no such file (nor a scene of that name)");
    if (std::filesystem::is_directory(path, ec))
        throw InputError(path, "", "is a folder; name a file in it");
    std::string name = std::filesystem::path(path).filename().string();
    for (char& c : name) c = char(std::tolower(static_cast<unsigned char>(c)));
    const auto endsWith = [&](const char* tail) {
        const size_t n = std::strlen(tail);
        return name.size() >= n && name.compare(name.size() - n, n, tail) == 0;
    };
    if (endsWith(".obj") || endsWith(".ply") || endsWith(".ply.gz") || endsWith(".rtmodel"))
        return PrintModel(path);
    if (endsWith(".json") || IsGltfPath(path)) return PrintScene(path);
    // Any other name is a scene file if it holds a JSON object, as render reads it ("G.Json",
    // "a.scene"); info had taken it for a mesh of an unknown extension.
    if (!std::filesystem::is_regular_file(path, ec))
        throw InputError(path, "", "not a regular file");
    std::ifstream in(path, std::ios::binary);
    char first = 0;
    while (in.get(first) && std::isspace(static_cast<unsigned char>(first))) {
    }
    if (in && first == '{') return PrintScene(path);
    throw InputError(path, "",
                     "unknown kind of file: info reads a mesh (.obj, .ply, .ply.gz), an .rtmodel, "
                     "a scene file (a JSON object) or a glTF file (.gltf, .glb)");
}

}  // namespace

void AddInfoCommand(CLI::App& app, int* exitCode) {
    auto path = std::make_shared<std::string>();
    CLI::App* cmd = app.add_subcommand(
        "info",
        "Describe a mesh, an .rtmodel, a scene file or a glTF file: counts, bounds, materials, "
        "lights, cameras, animation, nodes, BVH statistics");
    cmd->add_option(
           "file", *path,
           "Mesh (.obj, .ply, .ply.gz), .rtmodel, scene file (.json) or glTF (.gltf, .glb)")
        ->required();
    cmd->callback([path, exitCode] {
        RunInfo(*path);
        *exitCode = kExitOk;
    });
}

}  // namespace rtrt
