#include "game/scene/json_fields.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <sstream>
#include <string>
#include <unordered_set>
#include <vector>

#include "engine/core/error.h"

namespace rtrt {
namespace {

std::string Format(float v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

// "line L, column C" of a byte offset (both from 1).
std::string TextPosition(const std::string& text, size_t offset) {
    offset = std::min(offset, text.size());
    size_t line = 1, column = 1;
    for (size_t i = 0; i < offset; ++i) {
        if (text[i] == '\n') {
            ++line;
            column = 1;
        } else {
            ++column;
        }
    }
    return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

// Where the string token starting at text[i] ('"') ends (one past its closing quote).
size_t StringEnd(const std::string& text, size_t i) {
    for (++i; i < text.size(); ++i) {
        if (text[i] == '\\')
            ++i;
        else if (text[i] == '"')
            return i + 1;
    }
    return text.size();
}

// The offset of the n-th object key (from 0) of JSON text that is valid up to it: keys are the
// string tokens followed by a colon, in the order the parser reports them.
size_t NthKeyOffset(const std::string& text, size_t n) {
    for (size_t i = 0; i < text.size(); ++i) {
        if (text[i] != '"') continue;
        const size_t start = i, end = StringEnd(text, i);
        size_t next = end;
        while (next < text.size() && std::isspace(static_cast<unsigned char>(text[next]))) ++next;
        if (next < text.size() && text[next] == ':' && n-- == 0) return start;
        i = end - 1;
    }
    return text.size();
}

// The first number token whose value overflows a double (what nlohmann reports without a place).
size_t OverflowOffset(const std::string& text) {
    for (size_t i = 0; i < text.size(); ++i) {
        if (text[i] == '"') {
            i = StringEnd(text, i) - 1;
            continue;
        }
        const bool startsNumber =
            text[i] == '-' || std::isdigit(static_cast<unsigned char>(text[i]));
        if (!startsNumber) continue;
        size_t end = i;
        while (end < text.size() && std::strchr("+-0123456789.eE", text[end])) ++end;
        if (std::isinf(std::strtod(text.substr(i, end - i).c_str(), nullptr))) return i;
        i = end - 1;
    }
    return 0;
}

std::string NumberAt(const std::string& text, size_t at) {
    size_t end = at;
    while (end < text.size() && std::strchr("+-0123456789.eE", text[end])) ++end;
    return text.substr(at, std::min<size_t>(end - at, 40));
}

// The parser's complaint in rtrt's words where it is a common one.
std::string ParseErrorReason(const std::string& text, const Json::parse_error& e) {
    const size_t at = e.byte == 0 ? 0 : std::min(text.size(), size_t(e.byte - 1));
    // The invalid literal starts at the last token the parser read, before `at`.
    size_t start = at;
    while (start > 0 && std::isalpha(static_cast<unsigned char>(text[start - 1]))) --start;
    const std::string word = text.substr(start, 8);
    for (const char* nonNumber : {"NaN", "Infinity", "inf", "nan"})
        if (word.rfind(nonNumber, 0) == 0)
            return std::string(nonNumber) + " is not a JSON number; give a finite number";
    // Text after a whole JSON value: nlohmann "expected end of input" there.
    if (std::string(e.what()).find("; expected end of input") != std::string::npos)
        return "text after the end of the JSON (a file holds one JSON value)";
    // Where the text ends nlohmann says so; a last character that is wrong is named as it is.
    if (e.byte > text.size() || std::string(e.what()).find("end of input") != std::string::npos)
        return "the text ends before the JSON does (truncated?)";
    // nlohmann's text after its own "parse error at line L, column C: ".
    const std::string what = e.what();
    const size_t colon = what.find(": ", what.find("column"));
    return colon == std::string::npos ? what : what.substr(colon + 2);
}

}  // namespace

namespace {

// A key given twice in one object: a pass of its own over the text, since nlohmann's parse with a
// callback (3.11) rescans an object's parent at the end of every object, which took a scene of
// 400,000 objects 48 s. Counts keys as they come, so that the duplicate's place can be found.
class DuplicateKeyFinder : public nlohmann::json_sax<Json> {
  public:
    bool null() override { return true; }
    bool boolean(bool) override { return true; }
    bool number_integer(number_integer_t) override { return true; }
    bool number_unsigned(number_unsigned_t) override { return true; }
    bool number_float(number_float_t, const string_t&) override { return true; }
    bool string(string_t&) override { return true; }
    bool binary(binary_t&) override { return true; }
    bool start_object(std::size_t) override {
        objects_.emplace_back();
        return true;
    }
    bool key(string_t& key) override {
        if (!objects_.back().insert(key).second) {
            duplicate_ = key;
            return false;  // stops the pass here
        }
        ++keysSeen_;
        return true;
    }
    bool end_object() override {
        objects_.pop_back();
        return true;
    }
    bool start_array(std::size_t) override { return true; }
    bool end_array() override { return true; }
    bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override {
        return false;  // the text's own errors are the parse's to report
    }

    const std::optional<std::string>& Duplicate() const { return duplicate_; }
    size_t KeysBefore() const { return keysSeen_; }

  private:
    std::vector<std::unordered_set<std::string>> objects_;  // each open object's keys
    size_t keysSeen_ = 0;
    std::optional<std::string> duplicate_;
};

}  // namespace

Json ParseJson(const std::string& text, const std::string& file, DuplicateKeys duplicates) {
    // nlohmann's parser takes a NUL byte for the end of the text: what followed one was ignored.
    // NULs at the very end are padding (some writers pad a GLB's JSON chunk with them) and end the
    // text; one before the JSON's end is refused.
    const size_t nul = text.find('\0');
    if (nul != std::string::npos &&
        text.find_first_not_of(std::string(" \t\r\n\0", 5), nul) != std::string::npos)
        throw InputError(file, "",
                         TextPosition(text, nul) +
                             ": malformed JSON: a NUL byte (a JSON text holds none; binary file?)");
    if (nul != std::string::npos) return ParseJson(text.substr(0, nul), file, duplicates);
    Json parsed;
    try {
        parsed = Json::parse(text);
    } catch (const Json::parse_error& e) {
        throw InputError(file, "",
                         TextPosition(text, e.byte == 0 ? 0 : e.byte - 1) +
                             ": malformed JSON: " + ParseErrorReason(text, e));
    } catch (const Json::out_of_range&) {  // a number beyond double's range, such as 1e999
        const size_t at = OverflowOffset(text);
        throw InputError(file, "",
                         TextPosition(text, at) + ": malformed JSON: the number " +
                             NumberAt(text, at) + " is beyond the range of a double");
    }
    if (duplicates == DuplicateKeys::kError) {
        DuplicateKeyFinder finder;
        Json::sax_parse(text, &finder);
        if (const std::optional<std::string>& key = finder.Duplicate())
            throw InputError(file, "",
                             TextPosition(text, NthKeyOffset(text, finder.KeysBefore())) +
                                 ": malformed JSON: the key \"" + *key +
                                 "\" is given twice in one object");
    }
    return parsed;
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
        case JsonKind::kNumber:
            return v.is_number();
        case JsonKind::kString:
            return v.is_string();
        case JsonKind::kStrings:
            if (!v.is_array()) return false;
            for (const Json& x : v)
                if (!x.is_string()) return false;
            return true;
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
        case JsonKind::kNumber:
            return "a number";
        case JsonKind::kString:
            return "a string";
        case JsonKind::kStrings:
            return "an array of strings";
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

namespace {

// What v is, for a message: its JSON type, and for an array its first element that is not what
// the kind wants or its length ("got array" alone did not say what was wrong with it).
std::string Described(const Json& v, JsonKind kind) {
    const std::string type = v.type_name();
    const bool objects = kind == JsonKind::kObjects, ints = kind == JsonKind::kInts;
    const bool strings = kind == JsonKind::kStrings;
    const bool numbers =
        kind == JsonKind::kNumbers3 || kind == JsonKind::kNumbers4 || kind == JsonKind::kNumbers16;
    if (!v.is_array() || !(objects || ints || numbers || strings)) return type;
    if (v.empty()) return "an empty array";
    for (size_t i = 0; i < v.size(); ++i) {
        const Json& x = v[i];
        if (objects   ? x.is_object()
            : ints    ? x.is_number_integer()
            : strings ? x.is_string()
                      : x.is_number())
            continue;
        std::string shown = x.dump();
        if (shown.size() > 40) {
            size_t cut = 37;  // at a UTF-8 character's start
            while (cut > 0 && (static_cast<unsigned char>(shown[cut]) & 0xc0) == 0x80) --cut;
            shown = shown.substr(0, cut) + "...";
        }
        return "an array whose element " + std::to_string(i) + " is " + shown;
    }
    return "an array of " + std::to_string(v.size()) + (v.size() == 1 ? " element" : " elements");
}

}  // namespace

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
        Fail(key, std::string("expected ") + KindName(kind) + ", got " + Described(v, kind));
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
    // The value as written: 1e-50 is 0 as a float.
    if (!(v > 0.0f))
        Fail(key, "must be greater than 0, got " + (Has(key) ? j_.at(key).dump() : Format(v)));
    return v;
}

float JsonFields::InRange(const std::string& key, float lo, float hi, float fallback) {
    const float v = Number(key, fallback);
    // The value as written: its float can round to the bound it passes (1.0000001e9 to 1e9).
    if (!(v >= lo && v <= hi))
        Fail(key, "must be between " + Format(lo) + " and " + Format(hi) + ", got " +
                      (Has(key) ? j_.at(key).dump() : Format(v)));
    return v;
}

uint32_t JsonFields::Count(const std::string& key, uint32_t lo, uint32_t hi, uint32_t fallback) {
    if (!Has(key)) return fallback;
    ExpectKind(key, JsonKind::kInt);
    const Json& v = j_.at(key);
    // Values past int64's range are unsigned in the JSON: compared, and shown, as written (2^64-1
    // was shown as -1).
    const bool huge = v.is_number_unsigned() && v.get<uint64_t>() > uint64_t(INT64_MAX);
    const int64_t n = huge ? INT64_MAX : v.get<int64_t>();
    if (n < lo || n > hi)
        Fail(key, "must be between " + std::to_string(lo) + " and " + std::to_string(hi) +
                      ", got " + v.dump());
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

vec3 JsonFields::Position(const std::string& key, std::optional<vec3> fallback) {
    const vec3 p = Vec3(key, fallback);
    if (!(MaxComponent(glm::abs(p)) <= kMaxSceneCoordinate))
        Fail(key, "coordinates must be at most 1e7 in magnitude");
    return p;
}

vec3 JsonFields::Colour(const std::string& key, vec3 fallback) {
    const vec3 c = Has(key) && j_.at(key).is_number() ? vec3(Number(key)) : Vec3(key, fallback);
    if (c.x < 0 || c.y < 0 || c.z < 0) Fail(key, "colour components must not be negative");
    return c;
}

std::string JsonFields::String(const std::string& key, std::optional<std::string> fallback) {
    if (!Has(key)) {
        if (!fallback) Fail(key, "missing required field");
        return *fallback;
    }
    ExpectKind(key, JsonKind::kString);
    std::string value = j_.at(key).get<std::string>();
    // Names and paths end at a NUL where the system reads them: "tri.obj\u0000junk" had opened
    // tri.obj.
    if (value.find('\0') != std::string::npos)
        Fail(key, "holds a NUL character (\\u0000), which no name or path can");
    return value;
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
