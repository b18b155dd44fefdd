// Parsing JSON text as rtrt's scene files are parsed: a key given twice in one object is found
// where it is given again, in any object at any depth, and only there.
#include <gtest/gtest.h>

#include <string>

#include "engine/core/error.h"
#include "game/scene/json_fields.h"

namespace rtrt {
namespace {

std::string DuplicateError(const std::string& text) {
    try {
        ParseJson(text, "s.json", DuplicateKeys::kError);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

TEST(JsonParseTest, AKeyGivenTwiceInOneObjectIsFoundWhereItIsGivenAgain) {
    // The same key in sibling objects, in nested objects and in objects inside arrays is fine.
    EXPECT_EQ(
        DuplicateError(R"({"a": [{"a": 1}, {"a": 2}], "b": {"a": {"a": 3}}, "c": [[{"a": 0}]]})"),
        "");
    EXPECT_EQ(
        DuplicateError("{\"x\": {\"k\": 1,\n \"k\": 2}}"),
        "s.json: line 2, column 2: malformed JSON: the key \"k\" is given twice in one object");
    EXPECT_EQ(DuplicateError(R"([{"a": 1}, {"b": [{"c": 1, "d": 2, "c": 3}]}])"),
              "s.json: line 1, column 36: malformed JSON: the key \"c\" is given twice in one "
              "object");
    // An object closed before the key comes again does not count.
    EXPECT_EQ(DuplicateError(R"({"o": {"k": 1}, "p": {"k": 2}, "k": 3})"), "");
    // glTF's reading lets the later value win.
    EXPECT_EQ(ParseJson(R"({"k": 1, "k": 2})", "m.gltf", DuplicateKeys::kLastWins)["k"], 2);
}

// A syntax error is the parse's to report, before any key check; a wrong last character is named
// as such, not as the text ending early.
TEST(JsonParseTest, MalformedTextIsReportedBeforeAnyKeyCheck) {
    EXPECT_EQ(DuplicateError(R"({"k": 1, "k": })"),
              "s.json: line 1, column 15: malformed JSON: syntax error while parsing value - "
              "unexpected '}'; expected '[', '{', or a literal");
    EXPECT_EQ(DuplicateError(R"({"k": 1, "k": )"),
              "s.json: line 1, column 15: malformed JSON: the text ends before the JSON does "
              "(truncated?)");
    // Text after a whole value is the opposite of a truncated file.
    EXPECT_EQ(DuplicateError("{\"models\": {}}\n{\"models\": {}}\n"),
              "s.json: line 2, column 1: malformed JSON: text after the end of the JSON (a file "
              "holds one JSON value)");
    EXPECT_EQ(DuplicateError("{}}"),
              "s.json: line 1, column 3: malformed JSON: text after the end of the JSON (a file "
              "holds one JSON value)");
}

// nlohmann's parser takes a NUL byte for the end of the text: what followed one had been ignored.
TEST(JsonParseTest, ANulByteIsRefusedWhereItIs) {
    const std::string text = std::string("{ \"instances\": [] }\n") + '\0' + "{\"x\": garbage";
    EXPECT_EQ(DuplicateError(text),
              "s.json: line 2, column 1: malformed JSON: a NUL byte (a JSON text holds none; "
              "binary file?)");
    // NULs at the end are padding (a GLB's JSON chunk padded with them had loaded, and must).
    EXPECT_EQ(ParseJson(std::string("{\"k\": 1}  ") + std::string(3, '\0'), "m.glb",
                        DuplicateKeys::kLastWins)["k"],
              1);
    // An escaped NUL inside a string is JSON; the fields that read names refuse it.
    EXPECT_EQ(ParseJson(R"({"k": "a\u0000b"})", "s.json", DuplicateKeys::kError)["k"]
                  .get<std::string>()
                  .size(),
              3u);
}

}  // namespace
}  // namespace rtrt
