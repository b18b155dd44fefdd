#include "game/scene/json_fields.h"

#include <cmath>
#include <sstream>

#include "engine/core/error.h"

namespace rtrt {
namespace {

std::string Format(float v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

}  // namespace

Json ParseJson(const std::string& text, const std::string& file) {
    try {
        return Json::parse(text);
    } catch (const Json::exception& e) {  // parse_error, or out_of_range for 1e999
        throw InputError(file, "", std::string("malformed JSON: ") + e.what());
    }
}

std::string JsonIndexed(const std::string& array, size_t i) {
    return array + "[" + std::to_string(i) + "]";
}

bool IsKind(const Json& v, JsonKind kind) {
    auto numbers = [&](size_t n) {
        if (!v.is_array() || v.size() != n) return false;
        for (const Json& x : v)
            if (!x.is_number()) return false;
        return true;
    };
    switch (kind) {
        case JsonKind::kInt:
            return v.is_number_integer();
        case JsonKind::kString:
            return v.is_string();
        case JsonKind::kBool:
            return v.is_boolean();
        case JsonKind::kObject:
            return v.is_object();
        case JsonKind::kNumbers3:
            return numbers(3);
        case JsonKind::kNumbers4:
            return numbers(4);
        case JsonKind::kNumbers16:
            return numbers(16);
        case JsonKind::kInts:
        case JsonKind::kObjects:
            if (!v.is_array()) return false;
            for (const Json& x : v)
                if (kind == JsonKind::kInts ? !x.is_number_integer() : !x.is_object()) return false;
            return true;
    }
    return false;
}

const char* KindName(JsonKind kind) {
    switch (kind) {
        case JsonKind::kInt:
            return "an integer";
        case JsonKind::kString:
            return "a string";
        case JsonKind::kBool:
            return "true or false";
        case JsonKind::kObject:
            return "an object";
        case JsonKind::kInts:
            return "an array of integers";
        case JsonKind::kNumbers3:
            return "an array of 3 numbers";
        case JsonKind::kNumbers4:
            return "an array of 4 numbers";
        case JsonKind::kNumbers16:
            return "an array of 16 numbers";
        case JsonKind::kObjects:
            return "an array of objects";
    }
    return "";
}

JsonFields::JsonFields(const Json& j, std::string path, const std::string& file)
    : j_(j), path_(std::move(path)), file_(file) {
    if (!j.is_object()) Fail("", std::string("expected an object, got ") + j.type_name());
}

bool JsonFields::Has(const std::string& key) {
    allowed_.insert(key);
    return j_.contains(key);
}

const Json& JsonFields::Get(const std::string& key) {
    if (!Has(key)) Fail(key, "missing required field");
    return j_.at(key);
}

void JsonFields::ExpectKind(const std::string& key, JsonKind kind) {
    if (!Has(key)) return;
    const Json& v = j_.at(key);
    if (!IsKind(v, kind))
        Fail(key, std::string("expected ") + KindName(kind) + ", got " + v.type_name());
}

float JsonFields::Number(const std::string& key, std::optional<float> fallback) {
    if (!Has(key)) {
        if (!fallback) Fail(key, "missing required field");
        return *fallback;
    }
    return ToNumber(j_.at(key), key);
}

float JsonFields::Positive(const std::string& key, std::optional<float> fallback) {
    const float v = Number(key, fallback);
    if (!(v > 0.0f)) Fail(key, "must be greater than 0, got " + Format(v));
    return v;
}

float JsonFields::InRange(const std::string& key, float lo, float hi, float fallback) {
    const float v = Number(key, fallback);
    if (!(v >= lo && v <= hi))
        Fail(key, "must be between " + Format(lo) + " and " + Format(hi) + ", got " + Format(v));
    return v;
}

uint32_t JsonFields::Count(const std::string& key, uint32_t lo, uint32_t hi, uint32_t fallback) {
    if (!Has(key)) return fallback;
    ExpectKind(key, JsonKind::kInt);
    const int64_t n = j_.at(key).get<int64_t>();
    if (n < lo || n > hi)
        Fail(key, "must be between " + std::to_string(lo) + " and " + std::to_string(hi) +
                      ", got " + std::to_string(n));
    return uint32_t(n);
}

vec3 JsonFields::Vec3(const std::string& key, std::optional<vec3> fallback) {
    if (!Has(key)) {
        if (!fallback) Fail(key, "missing required field");
        return *fallback;
    }
    const Json& v = j_.at(key);
    // Unlike ExpectKind's message, this one says how many elements a wrong-sized array has.
    if (!v.is_array() || v.size() != 3)
        Fail(key, std::string("expected an array of 3 numbers, got ") +
                      (v.is_array() ? std::to_string(v.size()) + " elements" : v.type_name()));
    return vec3(ToNumber(v[0], key + "[0]"), ToNumber(v[1], key + "[1]"),
                ToNumber(v[2], key + "[2]"));
}

vec3 JsonFields::Colour(const std::string& key, vec3 fallback) {
    if (Has(key) && j_.at(key).is_number()) return vec3(Number(key));
    const vec3 c = Vec3(key, fallback);
    if (c.x < 0 || c.y < 0 || c.z < 0) Fail(key, "colour components must not be negative");
    return c;
}

std::string JsonFields::String(const std::string& key, std::optional<std::string> fallback) {
    if (!Has(key)) {
        if (!fallback) Fail(key, "missing required field");
        return *fallback;
    }
    ExpectKind(key, JsonKind::kString);
    return j_.at(key).get<std::string>();
}

void JsonFields::Finish() {
    for (const auto& [key, value] : j_.items()) {
        if (allowed_.count(key)) continue;
        std::string known;
        for (const std::string& k : allowed_) known += (known.empty() ? "" : ", ") + k;
        Fail(key, "unknown field (known fields here: " + known + ")");
    }
}

std::string JsonFields::Path(const std::string& key) const {
    if (key.empty()) return path_;
    return path_.empty() ? key : path_ + "." + key;
}

void JsonFields::Fail(const std::string& key, const std::string& reason) const {
    throw InputError(file_, Path(key), reason);
}

float JsonFields::ToNumber(const Json& v, const std::string& key) const {
    if (!v.is_number()) Fail(key, std::string("expected a number, got ") + v.type_name());
    const double d = v.get<double>();
    if (!std::isfinite(d) || std::fabs(d) > 3.0e38) Fail(key, "number out of range");
    return float(d);
}

}  // namespace rtrt
