// The one line an error prints: FILE: FIELD: REASON, whatever the user or the file gave.
#include "engine/core/error.h"

#include <gtest/gtest.h>

#include <string>

namespace rtrt {
namespace {

// A newline in a path had split the line, an escape sequence reached the terminal, and a NUL ended
// the message; UTF-8 names stay readable.
TEST(ErrorTest, ControlCharactersAreShownEscapedInTheLine) {
    EXPECT_EQ(WithoutControlCharacters(std::string("a\nb\x1b[31m\0\x7f", 10)),
              "a\\x0ab\\x1b[31m\\x00\\x7f");
    EXPECT_EQ(WithoutControlCharacters("caf\xc3\xa9 \t"), "caf\xc3\xa9 \\x09");
    // C1 controls as bytes (0x9b is CSI on 8-bit terminals) and in UTF-8 (U+009B), bytes that
    // are no UTF-8, and a right-to-left override (U+202E); other characters pass.
    EXPECT_EQ(WithoutControlCharacters("a\x9b"
                                       "2J"),
              "a\\x9b2J");
    EXPECT_EQ(WithoutControlCharacters("a\xc2\x9b"
                                       "2J"),
              "a\\xc2\\x9b2J");
    EXPECT_EQ(WithoutControlCharacters("\xe2\x80\xae"
                                       "gnp.exe"),
              "\\xe2\\x80\\xaegnp.exe");
    EXPECT_EQ(WithoutControlCharacters("\xc0\xaf \xff"), "\\xc0\\xaf \\xff");  // overlong, invalid
    EXPECT_EQ(WithoutControlCharacters("\xe2\x82\xac \xf0\x9f\x90\x89"),
              "\xe2\x82\xac \xf0\x9f\x90\x89");
    EXPECT_STREQ(InputError("no\nsuch/x.png", "", "the folder does not exist").what(),
                 "no\\x0asuch/x.png: the folder does not exist");
    EXPECT_STREQ(InputError("s.json", "name", "bad \x1b]0;title\x07").what(),
                 "s.json: name: bad \\x1b]0;title\\x07");
    EXPECT_STREQ(OutputError("out\r.png", "No space left on device").what(),
                 "out\\x0d.png: No space left on device");
    // The parts stay as given, for callers that compare them.
    EXPECT_EQ(InputError("a\nb", "", "r").File(), "a\nb");
}

}  // namespace
}  // namespace rtrt
