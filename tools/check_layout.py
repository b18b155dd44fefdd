#!/usr/bin/env python3
"""The layout rules of docs/architecture.md, checked over the tree (a ctest test runs this):
includes point one way between modules, no file includes a file that includes it back, and no
source file is over 600 lines. Prints each breach as FILE: reason and exits 1 if there is one."""
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SOURCES = (".h", ".cpp", ".cu", ".cuh")
MAX_LINES = 600

# What each module may include besides itself (and system or third-party headers).
ALLOWED = {
    "engine/core": [],
    "engine/ecs": ["engine/core"],
    "engine/physics_anim": ["engine/core", "engine/ecs"],
    "engine/geometry": ["engine/core"],
    "engine/bvh": ["engine/core", "engine/geometry"],
    "engine/render_rt": ["engine/core", "engine/geometry", "engine/bvh"],
    # The image library (OpenImageIO's formats, a module loaded at run time) serves image files
    # and glTF images alike.
    "game/image_library": ["engine"],
    "game/assets": ["engine", "game/image_library"],
    # The scene description (rtrt::scene_desc) is two files of game/scene that glTF and the
    # runtime build on; the scene files above them use glTF and the asset loaders.
    "game/gltf": ["engine", "game/scene/loaded_scene.h", "game/scene/json_fields.h",
                  "game/image_library"],
    "game/scene": ["engine", "game/gltf", "game/assets"],
    "game/runtime": ["engine", "game/scene/loaded_scene.h"],
    "game/farm": ["engine", "game/scene/json_fields.h"],
    "game/app": ["engine", "game"],
    "game/cli": ["engine", "game", "bench"],  # main registers `rtrt bench`
    "bench": ["engine", "game", "bench"],
    "tests": ["engine", "game", "bench", "tests"],
}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def module_of(path):
    for module in sorted((m for m in ALLOWED if not m.endswith(".h")), key=len, reverse=True):
        if path == module or path.startswith(module + "/"):
            return module
    return None


def sources():
    for top in ("engine", "game", "bench", "tests"):
        for folder, _, names in os.walk(os.path.join(ROOT, top)):
            for name in names:
                if name.endswith(SOURCES):
                    yield os.path.relpath(os.path.join(folder, name), ROOT)


def main():
    problems = []
    graph = {}
    for path in sorted(sources()):
        with open(os.path.join(ROOT, path), encoding="utf-8") as f:
            text = f.read()
        lines = text.count("\n")
        if lines > MAX_LINES:
            problems.append(f"{path}: {lines} lines, over {MAX_LINES}: split it by concern")
        own = module_of(path)
        includes = [i for i in INCLUDE.findall(text) if module_of(i) is not None]
        graph[path] = includes
        for inc in includes:
            target = module_of(inc)
            if target == own or any(inc == a or inc.startswith(a + "/") for a in ALLOWED[own]):
                continue
            problems.append(f"{path}: includes {inc}, but {own} may not depend on {target}")
    # Include cycles: a depth-first search over the project's own headers.
    state = {}

    def visit(node, stack):
        state[node] = 1
        stack.append(node)
        for nxt in graph.get(node, []):
            if state.get(nxt) == 1:
                cycle = stack[stack.index(nxt):] + [nxt]
                problems.append(f"{node}: include cycle {' -> '.join(cycle)}")
            elif nxt not in state and nxt in graph:
                visit(nxt, stack)
        stack.pop()
        state[node] = 2

    for node in graph:
        if node not in state:
            visit(node, [])
    for p in problems:
        print(p)
    if problems:
        print(f"check_layout: {len(problems)} breach(es) of the rules in docs/architecture.md")
        return 1
    print(f"check_layout: {len(graph)} files follow the layout rules")
    return 0


if __name__ == "__main__":
    sys.exit(main())
