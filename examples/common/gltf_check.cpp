// glTF before assimp: assimp's JSON reader recurses per nesting level and its importer per node level (a
// 30,000-deep node chain or JSON nested 1,000,000 deep overflows the stack), it allocates what a GLB's
// chunk header claims (0xFFFFFFF0 bytes for a 748-byte file), and PreTransformVertices copies a mesh
// once per node that uses it. All of that is read from the JSON here first, without recursion.
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <vector>

#include "model_checks.h"

namespace bricklight::scenes {

namespace {

using nlohmann::json;

std::string count(uint64_t n) { return std::to_string(n); }

// glTF 2 keeps objects in arrays and refers to them by index; glTF 1 keeps them in objects and refers
// to them by name. Both become an index here.
class Collection {
public:
    explicit Collection(const json* c) {
        if (!c) return;
        if (c->is_array()) {
            for (const json& item : *c) items_.push_back(&item);
        } else if (c->is_object()) {
            for (auto it = c->begin(); it != c->end(); ++it) {
                names_.push_back(it.key());
                items_.push_back(&it.value());
            }
        }
    }
    size_t size() const { return items_.size(); }
    const json& operator[](size_t i) const { return *items_[i]; }
    // The index a reference (a number in glTF 2, a name in glTF 1) stands for, or size() if none.
    size_t find(const json& reference) const {
        if (reference.is_number_unsigned() && reference.get<uint64_t>() < items_.size() && names_.empty())
            return size_t(reference.get<uint64_t>());
        if (reference.is_string())
            for (size_t i = 0; i < names_.size(); ++i)
                if (names_[i] == reference.get_ref<const std::string&>()) return i;
        return items_.size();
    }

private:
    std::vector<const json*> items_;
    std::vector<std::string> names_;
};

const json* member(const json& object, const char* name) {
    if (!object.is_object()) return nullptr;
    auto it = object.find(name);
    return it == object.end() ? nullptr : &*it;
}

uint64_t unsignedMember(const json& object, const char* name) {
    const json* v = member(object, name);
    return v && v->is_number_unsigned() ? v->get<uint64_t>() : 0;
}

class GltfChecker {
public:
    GltfChecker(const std::string& path, const json& root, const LoadLimits& limits, std::string* error)
        : path_(path), limits_(limits), error_(error), nodes_(member(root, "nodes")), meshes_(member(root, "meshes")),
          accessors_(member(root, "accessors")), buffers_(member(root, "buffers")), images_(member(root, "images")),
          materials_(member(root, "materials")) {}

    bool run() { return accessors() && buffers() && images() && materials() && nodes(); }

private:
    bool fail(const std::string& why) {
        if (error_) *error_ = "'" + path_ + "': " + why;
        return false;
    }

    bool accessors() {
        const uint64_t most = std::max(limits_.maxVertices, limits_.maxIndices);
        for (size_t i = 0; i < accessors_.size(); ++i) {
            const uint64_t n = unsignedMember(accessors_[i], "count");
            if (n > most)
                return fail("accessor " + count(i) + " holds " + count(n) + " elements, over the limit of " + count(most) + " " +
                            raiseHint(limits_.maxVertices >= limits_.maxIndices ? "maxVertices" : "maxIndices"));
        }
        return true;
    }

    bool buffers() {
        for (size_t i = 0; i < buffers_.size(); ++i) {
            const uint64_t n = unsignedMember(buffers_[i], "byteLength");
            if (n > limits_.maxFileBytes)
                return fail("buffer " + count(i) + " is " + count(n) + " bytes, over the limit of " + count(limits_.maxFileBytes) + " " +
                            raiseHint("maxFileBytes"));
        }
        return true;
    }

    bool images() {
        for (size_t i = 0; i < images_.size(); ++i) {
            const json* uri = member(images_[i], "uri");
            if (!uri || !uri->is_string()) continue;
            const std::string& text = uri->get_ref<const std::string&>();
            // assimp takes an empty uri for no texture and drops it without a word.
            if (text.empty()) return fail("image " + count(i) + "'s uri is empty (neither a file nor data)");
            if (text.rfind("data:", 0) != 0 && text.size() > kAssimpMaxName)
                return fail("image " + count(i) + "'s file name is " + count(text.size()) + " characters; assimp keeps at most " +
                            count(kAssimpMaxName) + " and would drop the texture");
        }
        return true;
    }

    // What assimp would silently turn into an opaque material: an alphaMode that is not one of the three glTF
    // names (they are case-sensitive: "mask" is not MASK), an alphaCutoff that is not a number.
    bool materials() {
        for (size_t i = 0; i < materials_.size(); ++i) {
            if (const json* mode = member(materials_[i], "alphaMode")) {
                const bool known = mode->is_string() && (*mode == "OPAQUE" || *mode == "MASK" || *mode == "BLEND");
                if (!known)
                    return fail("material " + count(i) + "'s alphaMode " + mode->dump().substr(0, 64) +
                                " is not \"OPAQUE\", \"MASK\" or \"BLEND\" (glTF's names, case-sensitive)");
            }
            if (const json* cutoff = member(materials_[i], "alphaCutoff"); cutoff && !cutoff->is_number())
                return fail("material " + count(i) + "'s alphaCutoff " + cutoff->dump().substr(0, 64) + " is not a number");
        }
        return true;
    }

    // The vertices and indices a mesh adds each time a node places it.
    void meshCost(const json& reference, uint64_t* vertices, uint64_t* indices) const {
        *vertices = *indices = 0;
        const size_t m = meshes_.find(reference);
        if (m >= meshes_.size()) return;
        const json* primitives = member(meshes_[m], "primitives");
        if (!primitives || !primitives->is_array()) return;
        for (const json& p : *primitives) {
            uint64_t n = 0;
            if (const json* attributes = member(p, "attributes"))
                if (const json* position = member(*attributes, "POSITION")) {
                    const size_t a = accessors_.find(*position);
                    if (a < accessors_.size()) n = unsignedMember(accessors_[a], "count");
                }
            *vertices += n;
            const json* index = member(p, "indices");
            const size_t a = index ? accessors_.find(*index) : accessors_.size();
            *indices += a < accessors_.size() ? unsignedMember(accessors_[a], "count") : n;
        }
    }

    bool nodes() {
        const size_t n = nodes_.size();
        if (n > limits_.maxNodes)
            return fail(count(n) + " nodes, over the limit of " + count(limits_.maxNodes) + " " + raiseHint("maxNodes"));
        // The hierarchy must be a tree (one parent each, no cycles); its depth, walked with a stack.
        std::vector<std::vector<size_t>> children(n);
        std::vector<uint32_t> parents(n, 0);
        for (size_t i = 0; i < n; ++i) {
            const json* list = member(nodes_[i], "children");
            if (!list || !list->is_array()) continue;
            for (const json& c : *list) {
                const size_t child = nodes_.find(c);
                if (child >= n) return fail("node " + count(i) + " names a child that does not exist");
                if (++parents[child] > 1) return fail("node " + count(child) + " has more than one parent (the nodes must form a tree)");
                children[i].push_back(child);
            }
        }
        uint64_t vertices = 0, indices = 0;
        size_t reached = 0;
        std::vector<std::pair<size_t, uint32_t>> stack;  // node, depth
        for (size_t i = 0; i < n; ++i)
            if (parents[i] == 0) stack.push_back({i, 1});
        while (!stack.empty()) {
            const auto [node, depth] = stack.back();
            stack.pop_back();
            ++reached;
            if (depth > limits_.maxNodeDepth)
                return fail("the node hierarchy is more than " + count(limits_.maxNodeDepth) + " levels deep " + raiseHint("maxNodeDepth"));
            if (const json* mesh = member(nodes_[node], "mesh")) {
                uint64_t v = 0, k = 0;
                meshCost(*mesh, &v, &k);
                vertices += v;
                indices += k;
                if (vertices > limits_.maxVertices)
                    return fail("its nodes place more than " + count(limits_.maxVertices) + " vertices " + raiseHint("maxVertices"));
                if (indices > limits_.maxIndices)
                    return fail("its nodes place more than " + count(limits_.maxIndices) + " vertex indices " + raiseHint("maxIndices"));
            }
            for (size_t c : children[node]) stack.push_back({c, depth + 1});
        }
        if (reached != n) return fail("its nodes form a cycle (the nodes must form a tree)");
        return true;
    }

    const std::string& path_;
    const LoadLimits& limits_;
    std::string* error_;
    Collection nodes_, meshes_, accessors_, buffers_, images_, materials_;
};

}  // namespace

uint64_t jsonNestingDepth(std::string_view json, uint64_t limit) {
    uint64_t depth = 0, deepest = 0;
    bool inString = false, escaped = false;
    for (const char c : json) {
        if (inString) {
            if (escaped) escaped = false;
            else if (c == '\\') escaped = true;
            else if (c == '"') inString = false;
            continue;
        }
        if (c == '"') {
            inString = true;
        } else if (c == '[' || c == '{') {
            deepest = std::max(deepest, ++depth);
            if (deepest > limit) return deepest;
        } else if ((c == ']' || c == '}') && depth > 0) {
            --depth;
        }
    }
    return deepest;
}

bool checkGltfJson(const std::string& path, std::string_view text, const LoadLimits& limits, std::string* error) {
    auto fail = [&](const std::string& why) {
        if (error) *error = "'" + path + "': " + why;
        return false;
    };
    if (text.size() > limits.maxJsonBytes)
        return fail("its JSON is " + count(text.size()) + " bytes, over the limit of " + count(limits.maxJsonBytes) + " " +
                    raiseHint("maxJsonBytes"));
    if (jsonNestingDepth(text, limits.maxJsonDepth) > limits.maxJsonDepth)
        return fail("its JSON nests more than " + count(limits.maxJsonDepth) + " levels deep " + raiseHint("maxJsonDepth"));
    // nlohmann's parser keeps its own stack (no recursion); the depth is bounded above anyway.
    const json root = json::parse(text.begin(), text.end(), nullptr, false);
    if (root.is_discarded()) return fail("its JSON does not parse");
    return GltfChecker(path, root, limits, error).run();
}

bool checkGlb(const std::string& path, std::string_view prefix, uint64_t fileSize, const LoadLimits& limits, std::string* error) {
    auto fail = [&](const std::string& why) {
        if (error) *error = "'" + path + "': " + why;
        return false;
    };
    auto u32 = [&](size_t at) {
        return uint32_t(uint8_t(prefix[at])) | uint32_t(uint8_t(prefix[at + 1])) << 8 | uint32_t(uint8_t(prefix[at + 2])) << 16 |
               uint32_t(uint8_t(prefix[at + 3])) << 24;
    };
    if (prefix.size() < 20 || prefix.compare(0, 4, "glTF") != 0) return fail("a GLB file needs a 12-byte header and a chunk header");
    const uint32_t version = u32(4), length = u32(8);
    if (length < 20) return fail("its GLB header claims " + count(length) + " bytes, too few for a header and a chunk");
    if (length > fileSize)
        return fail("its GLB header claims " + count(length) + " bytes but the file holds " + count(fileSize));
    uint64_t jsonOffset = 0, jsonLength = 0;
    if (version == 1) {  // header, then the content's length and format (0: JSON)
        jsonLength = u32(12);
        jsonOffset = 20;
    } else if (version == 2) {  // header, then chunks: length, type; the first is the JSON
        jsonLength = u32(12);
        jsonOffset = 20;
        if (u32(16) != 0x4E4F534Au) return fail("its first GLB chunk is not JSON");
        // Every chunk must fit in what the header says the file holds.
        uint64_t at = 12;
        for (int chunk = 0; at < length; ++chunk) {
            if (length - at < 8) return fail("GLB chunk " + std::to_string(chunk) + "'s header runs past the file");
            if (at + 8 > prefix.size()) break;  // beyond what was read: the JSON chunk and the next were checked
            const uint64_t chunkLength = u32(size_t(at));
            if (chunkLength > length - at - 8)
                return fail("GLB chunk " + std::to_string(chunk) + " claims " + count(chunkLength) + " bytes but only " +
                            count(length - at - 8) + " follow");
            at += 8 + chunkLength;
        }
    } else {
        return fail("GLB version " + count(version) + " is not 1 or 2");
    }
    if (jsonLength > limits.maxJsonBytes)
        return fail("its JSON chunk is " + count(jsonLength) + " bytes, over the limit of " + count(limits.maxJsonBytes) + " " +
                    raiseHint("maxJsonBytes"));
    if (jsonLength > uint64_t(length) - jsonOffset || jsonOffset + jsonLength > prefix.size())
        return fail("its JSON chunk claims " + count(jsonLength) + " bytes but the file holds " + count(fileSize));
    return checkGltfJson(path, prefix.substr(size_t(jsonOffset), size_t(jsonLength)), limits, error);
}

}  // namespace bricklight::scenes
