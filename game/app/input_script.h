#pragma once
// Scripted input for tests of the window (CI drives rtrt under Xvfb with it). One event per line,
// "FRAME COMMAND ARGS", '#' starts a comment:
//   key NAME           press a key (names as in the controls table: 1, F5, Space, Delete...)
//   click X Y          left button down and up at window pixel (X, Y)
//   drag X0 Y0 X1 Y1   left button down at (X0, Y0), moved to (X1, Y1) a frame later, released
//                      the frame after
//   look DX DY         the right button held while the mouse moves by (DX, DY)
//   screenshot PATH    write the frame shown (as rendered, before the overlay)
//   quit               close the window
// Events go through the same Input functions as GLFW's callbacks.
#include <string>
#include <vector>

#include "game/app/input.h"

namespace rtrt {

class InputScript {
  public:
    // Throws InputError (file, "line N", reason) for anything malformed. Screenshot paths are
    // checked as outputs are; one into pendingFolder, a folder the window makes once it opens
    // (play --record DIR), only for its format while that folder is missing.
    static InputScript Load(const std::string& path, const std::string& pendingFolder = "");

    struct Effects {
        std::vector<std::string> screenshots;
        bool quit = false;
    };
    // Feeds the events due at `frame` (and the releases that follow earlier ones) into input.
    Effects Apply(int frame, Input& input);
    // The frame after the last event's follow-ups (a drag's release), where a scripted run ends.
    int LastFrame() const;
    // The frame of the last event itself (-1: none).
    int LastEvent() const;

  private:
    struct Event {
        int frame = 0;
        std::string command;
        std::vector<std::string> text;
        std::vector<float> numbers;
        int key = -1;
    };
    std::vector<Event> events_;
};

}  // namespace rtrt
