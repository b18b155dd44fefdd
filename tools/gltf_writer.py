"""What the project's glTF-writing scripts (make_textured_gltf.py, make_pbr_gltf.py,
make_walker_gltf.py) share: an 8-bit RGB PNG encoder and the one binary buffer with its buffer
views and accessors, embedded as a base64 data URI."""
import base64, struct, zlib

def png(width, height, rgb):  # 8-bit RGB, rows top to bottom, no filtering (PNG spec, ISO 15948)
    def chunk(kind, data):
        return (struct.pack(">I", len(data)) + kind + data +
                struct.pack(">I", zlib.crc32(kind + data) & 0xffffffff))
    raw = b"".join(b"\0" + b"".join(bytes(rgb[y][x]) for x in range(width)) for y in range(height))
    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw, 9)) +
            chunk(b"IEND", b""))

class GltfBuffer:
    def __init__(self):
        self.data = bytearray()
        self.views, self.accessors = [], []

    def add(self, fmt, values, type_, count, component=5126, minmax=None, target=None):
        """Appends values (struct format fmt, 4-byte aligned) as a buffer view and an accessor over
        it; returns the accessor's index."""
        while len(self.data) % 4: self.data.append(0)
        offset = len(self.data)
        self.data.extend(struct.pack("<" + fmt * len(values), *values))
        self.views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(self.data) - offset})
        if target: self.views[-1]["target"] = target
        acc = {"bufferView": len(self.views) - 1, "componentType": component, "count": count,
               "type": type_}
        if minmax: acc["min"], acc["max"] = minmax
        self.accessors.append(acc)
        return len(self.accessors) - 1

    def buffers(self):
        return [{"byteLength": len(self.data), "uri": "data:application/octet-stream;base64," +
                 base64.b64encode(bytes(self.data)).decode()}]
