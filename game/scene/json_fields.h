#pragma once
// The one validated reader of JSON fields, shared by scene files and the glTF pre-checks: every
// defect is an InputError naming the file, the field ("instances[2].scale") and the reason.
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>

#include "engine/core/math.h"

namespace rtrt {

// The largest coordinate a scene may place anything at: beyond it 32-bit floats are too coarse to
// trace (a sphere 1e15 away vanished).
inline constexpr float kMaxSceneCoordinate = 1e7f;

using Json = nlohmann::json;

// Whether a key given twice in one object is an error (rtrt's scene files) or, as most JSON
// readers do, the later value wins (glTF, whose writers rtrt does not control).
enum class DuplicateKeys { kError, kLastWins };

// Parses TEXT; throws InputError(file, "", "line L, column C: malformed JSON: REASON") for text
// that is not JSON (NaN and Infinity named as such), holds a number beyond double's range (1e999),
// or, with DuplicateKeys::kError, gives a key twice in one object.
Json ParseJson(const std::string& text, const std::string& file,
               DuplicateKeys duplicates = DuplicateKeys::kError);

// "array[i]", the way messages name an element of an array.
std::string JsonIndexed(const std::string& array, size_t i);

// The JSON types a field can be required to have.
enum class JsonKind {
    kInt,
    kNumber,
    kString,
    kStrings,
    kBool,
    kObject,
    kInts,
    kNumbers3,
    kNumbers4,
    kNumbers16,
    kObjects
};
bool IsKind(const Json& v, JsonKind kind);
// As messages say it: "an integer", "an array of 3 numbers".
const char* KindName(JsonKind kind);

// One JSON object at a known path of FILE. Reading a key marks it as known; Finish() rejects any
// key nobody read, so a typo never passes silently (readers of formats that allow other keys, as
// glTF does, do not call it).
class JsonFields {
  public:
    JsonFields(const Json& j, std::string path, const std::string& file);

    bool Has(const std::string& key);
    const Json& Get(const std::string& key);
    // When KEY is present, it must be of KIND ("expected an integer, got string").
    void ExpectKind(const std::string& key, JsonKind kind);

    float Number(const std::string& key, std::optional<float> fallback = std::nullopt);
    float Positive(const std::string& key, std::optional<float> fallback = std::nullopt);
    float InRange(const std::string& key, float lo, float hi, float fallback);
    uint32_t Count(const std::string& key, uint32_t lo, uint32_t hi, uint32_t fallback);
    vec3 Vec3(const std::string& key, std::optional<vec3> fallback = std::nullopt);
    // A Vec3 that is a place in the scene: each coordinate at most kMaxSceneCoordinate in
    // magnitude (beyond it floats are too coarse to trace: objects vanished).
    vec3 Position(const std::string& key, std::optional<vec3> fallback = std::nullopt);
    // A colour: 3 numbers, or one number for grey.
    vec3 Colour(const std::string& key, vec3 fallback);
    std::string String(const std::string& key, std::optional<std::string> fallback = std::nullopt);

    void Finish();

    std::string Path(const std::string& key) const;
    [[noreturn]] void Fail(const std::string& key, const std::string& reason) const;

  private:
    float ToNumber(const Json& v, const std::string& key) const;

    const Json& j_;
    std::string path_;
    const std::string& file_;
    std::set<std::string> allowed_;
};

}  // namespace rtrt
