// libFuzzer target for the scene-file parser: any text must give a scene or an InputError, never
// a crash, a leak or undefined behaviour. Model files resolve against a folder that does not
// exist (and $RTRT_MODEL_DIR is set to one by the test), so only built-in shapes load.
#include <cstddef>
#include <cstdint>
#include <string>

#include "engine/core/error.h"
#include "game/scene/scene_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        const rtrt::LoadedScene scene =
            rtrt::ParseScene(text, "fuzz.json", "/nonexistent/rtrt-fuzz");
        volatile uint64_t touched = scene.scene.instances.size() + scene.entities.size();
        (void)touched;
    } catch (const rtrt::InputError&) {
    }
    return 0;
}
