#include "game/app/input_script.h"

#include <algorithm>
#include <charconv>
#include <climits>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "engine/core/error.h"
#include "engine/core/input_file.h"
#include "engine/core/output_file.h"
#include "game/app/controls.h"
#include "game/assets/image_io.h"
#include "game/assets/video_writer.h"

namespace rtrt {
namespace {

// How many numbers each command takes (-1: one word instead).
int Arity(const std::string& command) {
    if (command == "click" || command == "look") return 2;
    if (command == "drag") return 4;
    if (command == "key" || command == "screenshot") return -1;
    if (command == "quit") return 0;
    return -2;
}

// Scripts are a few lines of text: the bound keeps a huge file from filling memory.
constexpr size_t kMaxScriptBytes = size_t{16} << 20;

// The whole word as a frame number ("1.5" is not frame 1 followed by ".5").
bool ParseFrame(const std::string& word, long long* frame) {
    const char* end = word.data() + word.size();
    const char* first = word.starts_with("+") ? word.data() + 1 : word.data();  // as >> took it
    const auto [next, error] = std::from_chars(first, end, *frame);
    // Beyond a long long: out of the frames' range below, whichever sign.
    if (error == std::errc::result_out_of_range) *frame = word[0] == '-' ? -1 : LLONG_MAX;
    return next == end && (error == std::errc() || error == std::errc::result_out_of_range);
}

// WORD as a message quotes it: cut short, so that a line of five million letters is not repeated
// whole in a one-line error.
std::string Quoted(const std::string& word) {
    constexpr size_t kMaxQuoted = 64;
    return "\"" + (word.size() <= kMaxQuoted ? word : word.substr(0, kMaxQuoted) + "...") + "\"";
}

// Window pixels and mouse movements a script may give: 1e38 had overflowed the mouse position to
// inf and left the camera NaN for good.
constexpr float kMaxScriptCoordinate = 1e6f;

// FOLDER as the file system resolves it (links followed, "." and ".." gone, no trailing slash),
// so that two spellings of one folder compare equal.
std::filesystem::path ResolvedFolder(const std::string& folder) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path absolute = fs::absolute(folder.empty() ? "." : folder, ec);
    fs::path resolved = fs::weakly_canonical(absolute, ec);
    if (ec) resolved = absolute.lexically_normal();
    if (!resolved.has_filename()) resolved = resolved.parent_path();  // "DIR/"
    return resolved;
}

// Whether a screenshot would be written over by a frame of --record DIR (DIR/frame_NNNNN.png).
bool IsRecordedFrame(const std::string& shot, const std::string& recordFolder) {
    if (recordFolder.empty()) return false;
    const std::filesystem::path path(shot);
    return IsRecordedFrameName(path.filename().string()) &&
           ResolvedFolder(path.parent_path().string()) == ResolvedFolder(recordFolder);
}

// Whether a screenshot goes into the folder that does not exist yet but will (--record DIR).
bool IntoPendingFolder(const std::string& shot, const std::string& pendingFolder) {
    if (pendingFolder.empty()) return false;
    std::error_code ec;
    return !std::filesystem::exists(pendingFolder, ec) &&
           ResolvedFolder(std::filesystem::path(shot).parent_path().string()) ==
               ResolvedFolder(pendingFolder);
}

}  // namespace

InputScript InputScript::Load(const std::string& path, const std::string& pendingFolder) {
    // Read whole before the window opens: a FIFO or a device is refused, not waited on.
    std::istringstream in(ReadInputFile(path, kMaxScriptBytes));
    InputScript script;
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        const std::string field = "line " + std::to_string(number);
        // A UTF-8 byte order mark, which some editors put first, is no part of the first line.
        if (number == 1 && line.starts_with("\xEF\xBB\xBF")) line.erase(0, 3);
        if (const size_t hash = line.find('#'); hash != std::string::npos) line.resize(hash);
        std::istringstream words(line);
        Event e;
        std::string frameWord;
        long long frame = 0;
        if (!(words >> frameWord)) continue;  // blank or a comment
        if (!ParseFrame(frameWord, &frame))
            throw InputError(
                path, field,
                "expected FRAME COMMAND ARGS, with FRAME a whole number, got " + Quoted(frameWord));
        // Bounded so that an event's follow-up frames (LastFrame) stay within an int.
        constexpr int kMaxFrame = 100000000;
        if (frame < 0 || frame > kMaxFrame)
            throw InputError(path, field, "the frame must be >= 0 and at most 100000000");
        e.frame = int(frame);
        if (!(words >> e.command)) throw InputError(path, field, "missing command");
        const int arity = Arity(e.command);
        if (arity == -2)
            throw InputError(path, field,
                             "unknown command " + Quoted(e.command) +
                                 " (expected key, click, drag, look, screenshot or quit)");
        if (arity == -1) {
            std::string word;
            if (!(words >> word)) throw InputError(path, field, e.command + " needs an argument");
            e.text.push_back(word);
            if (e.command == "key" && (e.key = KeyByName(word)) < 0)
                throw InputError(path, field, "unknown key " + Quoted(word));
            // Checked now, not when the frame comes: a bad path fails before the window opens.
            if (e.command == "screenshot") {
                if (NameTheSameFile(word, path))
                    throw InputError(path, field,
                                     "screenshot " + Quoted(word) +
                                         " would be written over this script: name another file");
                // The scenes were loaded before: a screenshot over one of their files (a
                // texture) had failed only when its frame came, after the window opened.
                for (const std::string& asset : AssetFilesRead())
                    if (NameTheSameFile(word, asset))
                        throw InputError(path, field,
                                         "screenshot " + Quoted(word) +
                                             " would be written over a file of the scene (" +
                                             asset + "): name another file");
                if (IsRecordedFrame(word, pendingFolder))
                    throw InputError(path, field,
                                     "screenshot " + Quoted(word) +
                                         " would be written over by a frame of --record: name "
                                         "another file");
                try {
                    if (IntoPendingFolder(word, pendingFolder))
                        CheckImageFormat(word);
                    else
                        CheckImagePath(word);
                } catch (const InputError& bad) {
                    throw InputError(path, field, "screenshot " + word + ": " + bad.Reason());
                }
            }
        }
        for (int i = 0; i < arity; ++i) {
            std::string word;
            if (!(words >> word))
                throw InputError(path, field,
                                 e.command + " needs " + std::to_string(arity) + " numbers");
            float v = 0.0f;
            const char* end = word.data() + word.size();
            const auto [next, error] = std::from_chars(word.data(), end, v);
            if (next != end || error != std::errc() || !(std::fabs(v) <= kMaxScriptCoordinate))
                throw InputError(
                    path, field,
                    e.command + ": expected a number of pixels within 1e6, got " + Quoted(word));
            e.numbers.push_back(v);
        }
        std::string extra;
        if (words >> extra) throw InputError(path, field, "unexpected " + Quoted(extra));
        script.events_.push_back(std::move(e));
    }
    // In frame order, whatever the lines' order: a key pressed on the frame its earlier press is
    // released had been dropped when its line came first.
    std::stable_sort(script.events_.begin(), script.events_.end(),
                     [](const Event& a, const Event& b) { return a.frame < b.frame; });
    return script;
}

int InputScript::LastFrame() const {
    int last = 0;
    for (const Event& e : events_) last = std::max(last, e.frame + 2);
    return last;
}

int InputScript::LastEvent() const {
    int last = -1;
    for (const Event& e : events_) last = std::max(last, e.frame);
    return last;
}

InputScript::Effects InputScript::Apply(int frame, Input& input) {
    Effects effects;
    for (const Event& e : events_) {
        const int age = frame - e.frame;  // 0: due now; 1, 2: its follow-ups
        if (age < 0 || age > 2) continue;
        if (e.command == "key") {
            if (age == 0) input.Key(e.key, true);
            if (age == 1) input.Key(e.key, false);
        } else if (e.command == "click") {
            if (age == 0) {
                input.MouseMove(vec2(e.numbers[0], e.numbers[1]));
                input.MouseButton(0, true);
            }
            if (age == 1) input.MouseButton(0, false);
        } else if (e.command == "drag") {
            if (age == 0) {
                input.MouseMove(vec2(e.numbers[0], e.numbers[1]));
                input.MouseButton(0, true);
            }
            if (age == 1) input.MouseMove(vec2(e.numbers[2], e.numbers[3]));
            if (age == 2) input.MouseButton(0, false);
        } else if (e.command == "look") {
            if (age == 0) {
                input.MouseButton(1, true);
                input.MouseMove(input.mouse + vec2(e.numbers[0], e.numbers[1]));
            }
            if (age == 1) input.MouseButton(1, false);
        } else if (age == 0 && e.command == "screenshot") {
            effects.screenshots.push_back(e.text[0]);
        } else if (age == 0 && e.command == "quit") {
            effects.quit = true;
        }
    }
    return effects;
}

}  // namespace rtrt
