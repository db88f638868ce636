// PLY before assimp: assimp spins forever on a header without end_header, builds triangles from garbage
// for an ASCII face that lists more indices than its line holds, and crashes on a binary face whose list
// runs past the data. The whole body is walked here, element by element, without decoding more than the
// list lengths and the face indices.
#include <charconv>
#include <cstdint>
#include <cstring>
#include <vector>

#include "model_checks.h"

namespace bricklight::scenes {

namespace {

constexpr size_t kMaxHeaderBytes = 1 << 20;  // far more than any real header (comments included)

struct Property {
    std::string name;
    bool list = false;
    int countSize = 0;  // bytes of a list's length (binary)
    bool countSigned = false;
    int size = 0;  // bytes of a scalar, or of a list's items
    bool isSigned = false;
    bool isFloat = false;
};

struct Element {
    std::string name;
    uint64_t count = 0;
    std::vector<Property> properties;
};

bool scalarType(std::string_view t, int* size, bool* isSigned, bool* isFloat) {
    static const struct {
        const char* name;
        int size;
        bool isSigned, isFloat;
    } types[] = {{"char", 1, true, false},    {"int8", 1, true, false},    {"uchar", 1, false, false}, {"uint8", 1, false, false},
                 {"short", 2, true, false},   {"int16", 2, true, false},   {"ushort", 2, false, false}, {"uint16", 2, false, false},
                 {"int", 4, true, false},     {"int32", 4, true, false},   {"uint", 4, false, false},  {"uint32", 4, false, false},
                 {"float", 4, true, true},    {"float32", 4, true, true},  {"double", 8, true, true},  {"float64", 8, true, true}};
    for (const auto& type : types)
        if (t == type.name) {
            *size = type.size;
            *isSigned = type.isSigned;
            *isFloat = type.isFloat;
            return true;
        }
    return false;
}

std::vector<std::string_view> words(std::string_view line) {
    std::vector<std::string_view> out;
    size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
        const size_t start = i;
        while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
        if (i > start) out.push_back(line.substr(start, i - start));
    }
    return out;
}

bool isFaceIndices(const Element& e, const Property& p) {
    return e.name == "face" && (p.name == "vertex_indices" || p.name == "vertex_index");
}

class PlyChecker {
public:
    PlyChecker(const std::string& path, std::string_view bytes, const LoadLimits& limits, std::string* error)
        : path_(path), bytes_(bytes), limits_(limits), error_(error) {}

    bool run() {
        if (!header()) return false;
        for (const Element& e : elements_)
            if (e.name == "vertex") vertexCount_ = e.count;
        return format_ == "ascii" ? asciiBody() : binaryBody();
    }

private:
    bool fail(const std::string& why) {
        if (error_) *error_ = "'" + path_ + "': " + why;
        return false;
    }

    bool header() {
        size_t pos = 0, lineNumber = 0;
        const size_t end = std::min(bytes_.size(), kMaxHeaderBytes);
        while (true) {
            const size_t newline = bytes_.find('\n', pos);
            if (newline == std::string_view::npos || newline >= end)
                return fail("the PLY header has no end_header line in its first " + std::to_string(end) + " bytes");
            const std::vector<std::string_view> w = words(bytes_.substr(pos, newline - pos));
            pos = newline + 1;
            ++lineNumber;
            if (lineNumber == 1) {
                if (w.size() != 1 || w[0] != "ply") return fail("not a PLY file (no 'ply' line first)");
                continue;
            }
            if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
            if (w[0] == "end_header") break;
            if (w[0] == "format") {
                if (w.size() < 2 || (w[1] != "ascii" && w[1] != "binary_little_endian" && w[1] != "binary_big_endian"))
                    return fail("header line " + std::to_string(lineNumber) + ": unknown PLY format");
                format_ = std::string(w[1]);
            } else if (w[0] == "element") {
                Element e;
                const auto r = w.size() == 3 ? std::from_chars(w[2].data(), w[2].data() + w[2].size(), e.count) : std::from_chars_result{};
                if (w.size() != 3 || r.ec != std::errc() || r.ptr != w[2].data() + w[2].size())
                    return fail("header line " + std::to_string(lineNumber) + ": 'element' needs a name and a count");
                e.name = std::string(w[1]);
                elements_.push_back(std::move(e));
            } else if (w[0] == "property") {
                if (elements_.empty()) return fail("header line " + std::to_string(lineNumber) + ": a property before any element");
                Property p;
                bool ok;
                if (w.size() == 5 && w[1] == "list") {
                    bool countFloat = false;
                    ok = scalarType(w[2], &p.countSize, &p.countSigned, &countFloat) && !countFloat &&
                         scalarType(w[3], &p.size, &p.isSigned, &p.isFloat);
                    p.list = true;
                    p.name = std::string(w[4]);
                } else {
                    ok = w.size() == 3 && scalarType(w[1], &p.size, &p.isSigned, &p.isFloat);
                    p.name = w.size() == 3 ? std::string(w[2]) : std::string();
                }
                if (!ok) return fail("header line " + std::to_string(lineNumber) + ": unknown property type");
                elements_.back().properties.push_back(std::move(p));
            }
        }
        if (format_.empty()) return fail("the PLY header has no format line");
        body_ = pos;
        headerLines_ = lineNumber;
        for (const Element& e : elements_) {
            // Every element takes at least one byte of the body: a count beyond that is a lie.
            const bool takesSpace = !e.properties.empty();
            if (takesSpace && e.count > bytes_.size() - body_)
                return fail("element '" + e.name + "' claims " + std::to_string(e.count) + " entries, more than the file's " +
                            std::to_string(bytes_.size() - body_) + " bytes of data could hold");
            if (e.name == "vertex" && e.count > limits_.maxVertices)
                return fail(std::to_string(e.count) + " vertices, over the limit of " + std::to_string(limits_.maxVertices) + " " +
                            raiseHint("maxVertices"));
        }
        return true;
    }

    bool listLength(const Element& e, uint64_t index, const Property& p, uint64_t length) {
        if (length > limits_.maxFaceIndices)
            return fail(e.name + " " + std::to_string(index) + " lists " + std::to_string(length) + " values, over the limit of " +
                        std::to_string(limits_.maxFaceIndices) + " " + raiseHint("maxFaceIndices"));
        if (isFaceIndices(e, p)) {
            // assimp 5.2 aborts (an assertion in its triangulation) on a face without indices (found by
            // tests/fuzz/model_import_fuzzer.cpp).
            if (length == 0) return fail(e.name + " " + std::to_string(index) + " lists no vertex indices");
            indices_ += length;
            if (indices_ > limits_.maxIndices)
                return fail("the faces list more than " + std::to_string(limits_.maxIndices) + " vertex indices " + raiseHint("maxIndices"));
        }
        return true;
    }

    bool faceIndex(const Element& e, uint64_t index, int64_t vertex) {
        if (vertex < 0 || uint64_t(vertex) >= vertexCount_)
            return fail(e.name + " " + std::to_string(index) + " names vertex " + std::to_string(vertex) + " of " +
                        std::to_string(vertexCount_));
        return true;
    }

    uint64_t readUnsigned(size_t at, int size) const {
        uint64_t v = 0;
        const bool big = format_ == "binary_big_endian";
        for (int k = 0; k < size; ++k) {
            const uint8_t byte = uint8_t(bytes_[at + size_t(big ? k : size - 1 - k)]);
            v = (v << 8) | byte;
        }
        return v;
    }

    int64_t readInteger(size_t at, int size, bool isSigned) const {
        const uint64_t v = readUnsigned(at, size);
        if (!isSigned || size == 8) return int64_t(v);
        const uint64_t sign = uint64_t(1) << (8 * size - 1);
        return (v & sign) ? int64_t(v) - int64_t(sign << 1) : int64_t(v);
    }

    bool binaryBody() {
        size_t pos = body_;
        const size_t size = bytes_.size();
        for (const Element& e : elements_) {
            bool fixed = true;
            size_t stride = 0;
            for (const Property& p : e.properties) {
                fixed = fixed && !p.list;
                stride += size_t(p.size);
            }
            if (fixed) {  // all scalars: one multiplication, checked against what is left
                if (stride && e.count > (size - pos) / stride)
                    return fail("the file ends inside the " + std::to_string(e.count) + " '" + e.name + "' elements its header declares");
                pos += size_t(e.count) * stride;
                continue;
            }
            for (uint64_t i = 0; i < e.count; ++i)
                for (const Property& p : e.properties) {
                    if (!p.list) {
                        if (size - pos < size_t(p.size)) return fail("the file ends inside " + e.name + " " + std::to_string(i));
                        pos += size_t(p.size);
                        continue;
                    }
                    if (size - pos < size_t(p.countSize)) return fail("the file ends inside " + e.name + " " + std::to_string(i));
                    const int64_t length = readInteger(pos, p.countSize, p.countSigned);
                    pos += size_t(p.countSize);
                    if (length < 0) return fail(e.name + " " + std::to_string(i) + " lists a negative number of values");
                    if (!listLength(e, i, p, uint64_t(length))) return false;
                    if (uint64_t(length) > (size - pos) / size_t(p.size))
                        return fail(e.name + " " + std::to_string(i) + " lists " + std::to_string(length) + " values but the file ends after " +
                                    std::to_string((size - pos) / size_t(p.size)));
                    if (isFaceIndices(e, p)) {
                        if (p.isFloat) return fail("face indices must be integers");
                        for (int64_t k = 0; k < length; ++k)
                            if (!faceIndex(e, i, readInteger(pos + size_t(k) * size_t(p.size), p.size, p.isSigned))) return false;
                    }
                    pos += size_t(length) * size_t(p.size);
                }
        }
        return true;
    }

    bool asciiBody() {
        size_t pos = body_, lineNumber = headerLines_;
        auto nextLine = [&](std::vector<std::string_view>* w) {
            while (pos < bytes_.size()) {
                size_t newline = bytes_.find('\n', pos);
                if (newline == std::string_view::npos) newline = bytes_.size();
                *w = words(bytes_.substr(pos, newline - pos));
                pos = newline + 1;
                ++lineNumber;
                if (!w->empty()) return true;
            }
            return false;
        };
        std::vector<std::string_view> w;
        for (const Element& e : elements_) {
            if (e.properties.empty()) continue;
            for (uint64_t i = 0; i < e.count; ++i) {
                if (!nextLine(&w))
                    return fail("the file ends after " + std::to_string(i) + " of the " + std::to_string(e.count) + " '" + e.name +
                                "' elements its header declares");
                const std::string where = "line " + std::to_string(lineNumber) + ": " + e.name + " " + std::to_string(i);
                size_t t = 0;
                for (const Property& p : e.properties) {
                    if (t >= w.size()) return fail(where + " holds fewer values than its header's properties take");
                    if (!p.list) {
                        ++t;
                        continue;
                    }
                    uint64_t length = 0;
                    const auto r = std::from_chars(w[t].data(), w[t].data() + w[t].size(), length);
                    if (r.ec != std::errc() || r.ptr != w[t].data() + w[t].size())
                        return fail(where + ": a list length must be a whole number (got '" + std::string(w[t]) + "')");
                    ++t;
                    if (!listLength(e, i, p, length)) return false;
                    if (length > w.size() - t)
                        return fail(where + " lists " + std::to_string(length) + " values but its line holds " + std::to_string(w.size() - t));
                    if (isFaceIndices(e, p))
                        for (uint64_t k = 0; k < length; ++k) {
                            const std::string_view word = w[t + size_t(k)];
                            int64_t v = 0;
                            const auto rv = std::from_chars(word.data(), word.data() + word.size(), v);
                            if (rv.ec != std::errc() || rv.ptr != word.data() + word.size())
                                return fail(where + ": face index '" + std::string(word) + "' is not a whole number");
                            if (!faceIndex(e, i, v)) return false;
                        }
                    t += size_t(length);
                }
                if (t != w.size())
                    return fail(where + " holds " + std::to_string(w.size()) + " values where its header's properties take " + std::to_string(t));
            }
        }
        return true;
    }

    const std::string& path_;
    std::string_view bytes_;
    const LoadLimits& limits_;
    std::string* error_;
    std::string format_;
    std::vector<Element> elements_;
    size_t body_ = 0, headerLines_ = 0;
    uint64_t vertexCount_ = 0, indices_ = 0;
};

}  // namespace

bool checkPly(const std::string& path, std::string_view bytes, const LoadLimits& limits, std::string* error) {
    return PlyChecker(path, bytes, limits, error).run();
}

}  // namespace bricklight::scenes
