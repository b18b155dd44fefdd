#include "game/assets/ply_header.h"

#include <cstdio>
#include <string>

#include "engine/core/error.h"
#include "game/assets/mesh_text.h"

namespace rtrt {
namespace {

using mesh_text::kMaxVertices;
using mesh_text::NextWord;
using mesh_text::ParseNumber;
using mesh_text::Quote;

bool ParseScalarType(std::string_view name, ScalarType& type) {
    struct Named {
        std::string_view name;
        ScalarType type;
    };
    static constexpr std::array<Named, 16> kTypes = {{
        {"char", ScalarType::kInt8},
        {"int8", ScalarType::kInt8},
        {"uchar", ScalarType::kUint8},
        {"uint8", ScalarType::kUint8},
        {"short", ScalarType::kInt16},
        {"int16", ScalarType::kInt16},
        {"ushort", ScalarType::kUint16},
        {"uint16", ScalarType::kUint16},
        {"int", ScalarType::kInt32},
        {"int32", ScalarType::kInt32},
        {"uint", ScalarType::kUint32},
        {"uint32", ScalarType::kUint32},
        {"float", ScalarType::kFloat32},
        {"float32", ScalarType::kFloat32},
        {"double", ScalarType::kFloat64},
        {"float64", ScalarType::kFloat64},
    }};
    for (const Named& named : kTypes) {
        if (named.name == name) {
            type = named.type;
            return true;
        }
    }
    return false;
}

std::vector<std::string_view> SplitWords(std::string_view line) {
    std::vector<std::string_view> words;
    for (std::string_view word = NextWord(line); !word.empty(); word = NextWord(line)) {
        words.push_back(word);
    }
    return words;
}

PlyFormat ParsePlyFormat(const std::string& path, const std::string& field,
                         const std::vector<std::string_view>& words) {
    double version = 0.0;
    if (words.size() != 3 || !ParseNumber(words[2], version) || version != 1.0) {
        throw InputError(path, field, "expected 'format <type> 1.0'");
    }
    if (words[1] == "ascii") return PlyFormat::kAscii;
    if (words[1] == "binary_little_endian") return PlyFormat::kBinaryLittleEndian;
    if (words[1] == "binary_big_endian") return PlyFormat::kBinaryBigEndian;
    throw InputError(path, field, "unknown format " + Quote(words[1]));
}

// Parses "property <type> <name>" or "property list <count type> <item type> <name>".
PlyProperty ParsePlyProperty(const std::string& path, const std::string& field,
                             const std::vector<std::string_view>& words) {
    PlyProperty property;
    property.name = words.back();
    if (words.size() == 3 && ParseScalarType(words[1], property.type)) return property;
    property.isList = true;
    if (words.size() != 5 || words[1] != "list" || !ParseScalarType(words[2], property.countType) ||
        !ParseScalarType(words[3], property.type)) {
        throw InputError(path, field,
                         "expected 'property <type> <name>' or 'property list <count type> "
                         "<item type> <name>' with known types");
    }
    if (!IsInteger(property.countType)) {
        throw InputError(path, field, "list count type must be an integer type");
    }
    return property;
}

// The property NAME of ELEMENT, one rtrt reads, or -1. Named twice, it is refused: which of two
// x's is the vertex's own? The first had been taken without a word. (Properties rtrt skips may
// repeat: real files have such duplicates.)
int FindProperty(const std::string& path, const PlyElement& element, std::string_view name) {
    int found = -1;
    for (size_t i = 0; i < element.properties.size(); ++i) {
        if (element.properties[i].name != name) continue;
        if (found >= 0)
            throw InputError(
                path, "header",
                "element " + element.name + " has the property " + Quote(name) + " twice");
        found = static_cast<int>(i);
    }
    return found;
}

const PlyElement* FindElement(const std::string& path, const PlyHeader& header,
                              std::string_view name) {
    const PlyElement* found = nullptr;
    for (const PlyElement& element : header.elements) {
        if (element.name != name) continue;
        if (found) throw InputError(path, "header", "more than one element " + Quote(name));
        found = &element;
    }
    return found;
}

// The vertex_indices (or vertex_index) list of ELEMENT, or -1 without the element.
int IndexListProperty(const std::string& path, const PlyElement* element) {
    if (!element) return -1;
    int property = FindProperty(path, *element, "vertex_indices");
    if (property < 0) property = FindProperty(path, *element, "vertex_index");
    if (property < 0) {
        throw InputError(path, "header", element->name + " element has no vertex_indices list");
    }
    const PlyProperty& indices = element->properties[property];
    if (!indices.isList || !IsInteger(indices.type)) {
        throw InputError(path, "header",
                         element->name + " vertex_indices must be a list of integers");
    }
    return property;
}

}  // namespace

size_t SizeOf(ScalarType type) {
    switch (type) {
        case ScalarType::kInt8:
        case ScalarType::kUint8:
            return 1;
        case ScalarType::kInt16:
        case ScalarType::kUint16:
            return 2;
        case ScalarType::kInt32:
        case ScalarType::kUint32:
        case ScalarType::kFloat32:
            return 4;
        case ScalarType::kFloat64:
            return 8;
    }
    return 8;
}

bool IsInteger(ScalarType type) {
    return type != ScalarType::kFloat32 && type != ScalarType::kFloat64;
}

// Reads the header up to end_header; throws on anything it does not understand.
PlyHeader ParsePlyHeaderLines(const std::string& path, std::string_view data) {
    if (data.substr(0, 3) != "ply" || data.size() < 4 || (data[3] != '\n' && data[3] != '\r')) {
        throw InputError(path, "header", "bad magic (not a PLY file)");
    }
    // Lines end as the first one does. Old Mac tools end them with a lone CR; a CR-LF header's CR
    // is trimmed with the words. Deciding once keeps a binary body whose first byte is 0x0A
    // after an "end_header\r" from being taken for the rest of a line end.
    const char lineEnd = data[3] == '\r' && (data.size() < 5 || data[4] != '\n') ? '\r' : '\n';
    PlyHeader header;
    bool haveFormat = false;
    size_t offset = 0;
    for (size_t lineNumber = 1;; ++lineNumber) {
        size_t newline = data.find(lineEnd, offset);
        std::string field = "header line " + std::to_string(lineNumber);
        if (newline == std::string_view::npos) {
            throw InputError(path, field, "no end_header (truncated header)");
        }
        std::vector<std::string_view> words = SplitWords(data.substr(offset, newline - offset));
        offset = newline + 1;
        if (lineNumber == 1 || words.empty()) continue;
        std::string_view keyword = words[0];
        if (keyword == "comment" || keyword == "obj_info") continue;
        if (keyword == "end_header") {
            if (!haveFormat) throw InputError(path, field, "end_header before the format line");
            header.dataOffset = offset;
            return header;
        }
        if (keyword == "format") {
            header.format = ParsePlyFormat(path, field, words);
            haveFormat = true;
        } else if (keyword == "element") {
            PlyElement element;
            if (words.size() != 3 || !ParseNumber(words[2], element.count)) {
                throw InputError(path, field, "expected 'element <name> <count>'");
            }
            element.name = words[1];
            header.elements.push_back(std::move(element));
        } else if (keyword == "property") {
            if (header.elements.empty()) throw InputError(path, field, "property before element");
            header.elements.back().properties.push_back(ParsePlyProperty(path, field, words));
        } else {
            throw InputError(path, field, "unknown keyword " + Quote(keyword));
        }
    }
}

// A record takes at least its binary values' sizes (a list its count's), or in ASCII one character
// and one separator per value; the final newline of an ASCII file is optional.
void CheckPlyCounts(const std::string& path, const PlyHeader& header, size_t dataBytes) {
    bool ascii = header.format == PlyFormat::kAscii;
    uint64_t available = dataBytes + (ascii ? 1 : 0), needed = 0;
    for (const PlyElement& element : header.elements) {
        uint64_t recordBytes = 0;
        for (const PlyProperty& p : element.properties) {
            recordBytes += ascii ? 2 : SizeOf(p.isList ? p.countType : p.type);
        }
        if (element.count == 0) continue;
        if (recordBytes == 0) {
            throw InputError(path, "header",
                             "element " + Quote(element.name) + " has no properties");
        }
        if (element.count > (available - needed) / recordBytes) {
            throw InputError(path, "header",
                             "element " + Quote(element.name) + " declares " +
                                 std::to_string(element.count) + " records, more than the " +
                                 std::to_string(dataBytes) + " bytes of data can hold");
        }
        needed += element.count * recordBytes;
    }
}

PlyLayout FindPlyLayout(const std::string& path, const PlyHeader& header) {
    PlyLayout layout;
    layout.vertices = FindElement(path, header, "vertex");
    layout.faces = FindElement(path, header, "face");
    layout.strips = FindElement(path, header, "tristrips");
    if (!layout.vertices) throw InputError(path, "header", "no vertex element");
    if (layout.vertices->count > kMaxVertices) {
        throw InputError(path, "header", "more than 2^32 - 1 vertices");
    }
    static constexpr std::array<std::string_view, 6> kNames = {"x", "y", "z", "nx", "ny", "nz"};
    for (size_t i = 0; i < kNames.size(); ++i) {
        int index = FindProperty(path, *layout.vertices, kNames[i]);
        if (index >= 0 && layout.vertices->properties[index].isList) {
            throw InputError(path, "header", "vertex property " + Quote(kNames[i]) + " is a list");
        }
        if (index < 0 && i < 3) {
            throw InputError(path, "header", "vertex element has no property " + Quote(kNames[i]));
        }
        layout.vertexProperty[i] = index;
    }
    layout.hasNormals = layout.vertexProperty[3] >= 0 && layout.vertexProperty[4] >= 0 &&
                        layout.vertexProperty[5] >= 0;
    using Names = std::array<std::string_view, 3>;
    for (const Names& names :
         {Names{"red", "green", "blue"}, Names{"diffuse_red", "diffuse_green", "diffuse_blue"}}) {
        std::array<int, 3> found{-1, -1, -1};
        bool twice = false;
        for (size_t k = 0; k < 3; ++k)
            for (size_t i = 0; i < layout.vertices->properties.size(); ++i) {
                if (layout.vertices->properties[i].name != names[k]) continue;
                twice |= found[k] >= 0;
                found[k] = static_cast<int>(i);
                if (layout.vertices->properties[i].isList)
                    throw InputError(path, "header",
                                     "vertex property " + Quote(names[k]) + " is a list");
            }
        if (found[0] < 0 || found[1] < 0 || found[2] < 0) continue;
        // Real files repeat such properties; which one is the colour is anyone's guess.
        if (twice) {
            std::fprintf(stderr,
                         "rtrt: warning: %s: a vertex colour property (%s %s %s) is named twice; "
                         "the vertices' colours are not read\n",
                         WithoutControlCharacters(path).c_str(), std::string(names[0]).c_str(),
                         std::string(names[1]).c_str(), std::string(names[2]).c_str());
            break;
        }
        layout.colorProperty = found;
        layout.hasColors = true;
        break;
    }
    layout.faceIndexProperty = IndexListProperty(path, layout.faces);
    layout.stripIndexProperty = IndexListProperty(path, layout.strips);
    if (layout.faces)
        for (const PlyProperty& property : layout.faces->properties)
            if (property.name == "red" || property.name == "diffuse_red") {
                std::fprintf(stderr,
                             "rtrt: warning: %s: the faces' colours are not read (rtrt reads "
                             "colours per vertex); the faces take the model's material colour\n",
                             WithoutControlCharacters(path).c_str());
                break;
            }
    return layout;
}

}  // namespace rtrt
