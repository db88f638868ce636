// The "foliage" built-in scene: alpha-tested geometry as games build vegetation. A meadow of grass tufts
// (crossed vertical cards), a tree and a hedge of leaf cards, an opaque ground, trunk and wall, under sun and
// sky. The grass and leaf textures are generated here (no files). Units: metres. Placement comes from a fixed
// seed: every run builds the same scene.
#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "scene_geometry.h"

namespace bricklight::scenes {

namespace {

constexpr uint32_t kFoliageTextureSize = 256;  // the renderer's layer size: no resampling
constexpr float kPi = 3.14159265358979f;

// A small deterministic generator (the standard distributions differ between library implementations).
struct Random {
    uint32_t state;
    float next() {  // [0, 1)
        state = state * 747796405u + 2891336453u;
        uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
        word = (word >> 22u) ^ word;
        return float(word >> 8) * (1.0f / 16777216.0f);
    }
    float range(float lo, float hi) { return lo + (hi - lo) * next(); }
};

uint8_t srgbByte(float linear) {
    const float c = std::clamp(linear, 0.0f, 1.0f);
    const float s = c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
    return uint8_t(std::lround(s * 255.0f));
}

// Texels of `texture` from a coverage test and a colour per texel centre (u right, v down, both 0..1). Texels
// outside keep the mean colour of those inside, so that filtering across the cut-out edge does not darken it.
template <typename Inside, typename Colour>
std::shared_ptr<const GeneratedTexture> makeTexture(const char* name, Inside inside, Colour colour) {
    auto t = std::make_shared<GeneratedTexture>();
    t->name = name;
    t->width = t->height = kFoliageTextureSize;
    t->rgba.assign(size_t(kFoliageTextureSize) * kFoliageTextureSize * 4, 0);
    std::vector<bool> covered(size_t(kFoliageTextureSize) * kFoliageTextureSize);
    glm::vec3 sum(0.0f);
    size_t count = 0;
    for (uint32_t y = 0; y < kFoliageTextureSize; ++y)
        for (uint32_t x = 0; x < kFoliageTextureSize; ++x) {
            const float u = (float(x) + 0.5f) / kFoliageTextureSize, v = (float(y) + 0.5f) / kFoliageTextureSize;
            const size_t i = size_t(y) * kFoliageTextureSize + x;
            if (!inside(u, v)) continue;
            covered[i] = true;
            const glm::vec3 c = colour(u, v);
            sum += c;
            ++count;
            t->rgba[4 * i] = srgbByte(c.r);
            t->rgba[4 * i + 1] = srgbByte(c.g);
            t->rgba[4 * i + 2] = srgbByte(c.b);
            t->rgba[4 * i + 3] = 255;
        }
    const glm::vec3 mean = count ? sum / float(count) : glm::vec3(0.5f);
    for (size_t i = 0; i < covered.size(); ++i)
        if (!covered[i]) {
            t->rgba[4 * i] = srgbByte(mean.r);
            t->rgba[4 * i + 1] = srgbByte(mean.g);
            t->rgba[4 * i + 2] = srgbByte(mean.b);
        }
    return t;
}

// Tapered, slightly bent blades rising from the bottom edge of the card (v = 1): about 40 % coverage.
std::shared_ptr<const GeneratedTexture> grassTexture() {
    struct Blade {
        float base, lean, height, width;
    };
    std::vector<Blade> blades;
    Random r{0x67726173u};
    for (int i = 0; i < 14; ++i) {
        const float base = 0.06f + 0.88f * (float(i) + r.next()) / 14.0f;
        blades.push_back({base, r.range(-0.18f, 0.18f), r.range(0.55f, 0.98f), r.range(0.07f, 0.11f)});
    }
    auto inside = [blades](float u, float v) {
        for (const Blade& b : blades) {
            const float s = (1.0f - v) / b.height;  // 0 at the root, 1 at the tip
            if (s < 0.0f || s > 1.0f) continue;
            const float centre = b.base + b.lean * s * s;
            if (std::fabs(u - centre) < 0.5f * b.width * (1.0f - s)) return true;
        }
        return false;
    };
    auto colour = [](float, float v) {
        const float s = 1.0f - v;  // darker at the root, yellower towards the tips
        return glm::mix(glm::vec3(0.05f, 0.16f, 0.02f), glm::vec3(0.28f, 0.45f, 0.08f), s);
    };
    return makeTexture("grass blades", inside, colour);
}

// Pointed oval leaves on short stalks, in several directions over the card: about 45 % coverage.
std::shared_ptr<const GeneratedTexture> leafTexture() {
    struct Leaf {
        glm::vec2 stalk, axis;
        float length, width;
        float shade;
    };
    std::vector<Leaf> leaves;
    Random r{0x6c656166u};
    for (int i = 0; i < 9; ++i) {
        const float angle = r.range(0.0f, 2.0f * kPi);
        const glm::vec2 axis(std::cos(angle), std::sin(angle));
        const float length = r.range(0.38f, 0.5f);
        // Stalks around the centre, leaves pointing outwards, inside the card.
        const glm::vec2 stalk = glm::clamp(glm::vec2(0.5f) - axis * (0.5f * length) + glm::vec2(r.range(-0.2f, 0.2f), r.range(-0.2f, 0.2f)),
                                           glm::vec2(0.0f), glm::vec2(1.0f));
        leaves.push_back({stalk, axis, length, r.range(0.16f, 0.22f), r.range(0.7f, 1.0f)});
    }
    auto leafAt = [leaves](float u, float v) -> const Leaf* {
        for (const Leaf& l : leaves) {
            const glm::vec2 d = glm::vec2(u, v) - l.stalk;
            const float along = glm::dot(d, l.axis) / l.length, across = std::fabs(d.x * l.axis.y - d.y * l.axis.x);
            if (along < 0.0f || along > 1.0f) continue;
            // Widest a third of the way up, pointed at the tip.
            const float profile = along < 0.35f ? std::sin(along / 0.35f * 0.5f * kPi) : 1.0f - (along - 0.35f) / 0.65f;
            if (across < 0.5f * l.width * std::sqrt(std::max(profile, 0.0f))) return &l;
        }
        return nullptr;
    };
    auto inside = [leafAt](float u, float v) { return leafAt(u, v) != nullptr; };
    auto colour = [leafAt](float u, float v) {
        const Leaf* l = leafAt(u, v);
        return glm::vec3(0.07f, 0.22f, 0.04f) * (l ? l->shade : 1.0f);
    };
    return makeTexture("leaves", inside, colour);
}

// A vertical card `width` x `height` standing on `base`, turned by `angle` about the vertical, the texture
// upright (v = 0 at the top).
void addCard(TriangleMesh& m, glm::vec3 base, float angle, float width, float height) {
    const glm::vec3 side = glm::vec3(std::cos(angle), 0.0f, std::sin(angle)) * (0.5f * width);
    const uint32_t b = uint32_t(m.positions.size() / 3);
    for (const glm::vec3& p : {base - side, base + side, base + side + glm::vec3(0, height, 0), base - side + glm::vec3(0, height, 0)})
        m.positions.insert(m.positions.end(), {p.x, p.y, p.z});
    m.uvs.insert(m.uvs.end(), {0, 1, 1, 1, 1, 0, 0, 0});
    m.indices.insert(m.indices.end(), {b, b + 1, b + 2, b, b + 2, b + 3});
}

// A square card of side `size` centred on `centre` in the plane of the unit vectors `a` and `b`.
void addLeafCard(TriangleMesh& m, glm::vec3 centre, glm::vec3 a, glm::vec3 b, float size) {
    const uint32_t first = uint32_t(m.positions.size() / 3);
    const float h = 0.5f * size;
    for (const glm::vec3& p : {centre - a * h + b * h, centre + a * h + b * h, centre + a * h - b * h, centre - a * h - b * h})
        m.positions.insert(m.positions.end(), {p.x, p.y, p.z});
    m.uvs.insert(m.uvs.end(), {0, 1, 1, 1, 1, 0, 0, 0});
    m.indices.insert(m.indices.end(), {first, first + 1, first + 2, first, first + 2, first + 3});
}

// A card of random orientation.
void addRandomLeafCard(TriangleMesh& m, glm::vec3 centre, float size, Random& r) {
    const float z = r.range(-1.0f, 1.0f), phi = r.range(0.0f, 2.0f * kPi);
    const glm::vec3 normal(std::sqrt(1.0f - z * z) * std::cos(phi), z, std::sqrt(1.0f - z * z) * std::sin(phi));
    const glm::vec3 helper = std::fabs(normal.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    const glm::vec3 a = glm::normalize(glm::cross(helper, normal)), b = glm::cross(normal, a);
    addLeafCard(m, centre, a, b, size);
}

TriangleMesh opaque(const char* name, glm::vec3 albedo) {
    TriangleMesh m;
    m.name = name;
    m.albedo = albedo;
    return m;
}

TriangleMesh alphaTestedCards(const char* name, std::shared_ptr<const GeneratedTexture> texture) {
    TriangleMesh m;
    m.name = name;
    m.albedo = glm::vec3(1.0f);  // the texture's colour
    m.generatedTexture = std::move(texture);
    m.alphaCutoff = 0.5f;
    return m;
}

}  // namespace

SceneGeometry foliage() {
    SceneGeometry s;
    s.name = "foliage";
    auto add = [&](TriangleMesh m) {
        s.meshes.push_back(std::move(m));
        s.instances.push_back({uint32_t(s.meshes.size() - 1), glm::mat4(1.0f)});
    };
    // Ground 24 x 24 m (top at y = 0) and a wall 3 m high across the back (z = -7).
    TriangleMesh ground = opaque("ground", glm::vec3(0.22f, 0.17f, 0.1f));
    addBox(ground, {-12.0f, -0.2f, -12.0f}, {12.0f, 0.0f, 12.0f});
    add(std::move(ground));
    TriangleMesh wall = opaque("wall", glm::vec3(0.6f, 0.55f, 0.5f));
    addBox(wall, {-10.0f, 0.0f, -7.3f}, {10.0f, 3.0f, -7.0f});
    add(std::move(wall));
    // The tree's trunk (its crown is leaf cards) right of the view's centre.
    const glm::vec3 crown(2.5f, 3.2f, -3.5f);
    TriangleMesh trunk = opaque("trunk", glm::vec3(0.25f, 0.16f, 0.09f));
    addBox(trunk, {crown.x - 0.15f, 0.0f, crown.z - 0.15f}, {crown.x + 0.15f, crown.y - 0.3f, crown.z + 0.15f});
    add(std::move(trunk));

    // Grass: tufts of three cards crossing at 60 degrees on a jittered 0.35 m grid over 14 x 10 m in front of
    // the hedge (about 1190 tufts, 7100 triangles); the ground shows between them.
    Random r{0x666f6c69u};
    TriangleMesh grass = alphaTestedCards("grass", grassTexture());
    for (float z = -5.4f; z < 4.6f; z += 0.35f)
        for (float x = -7.0f; x < 7.0f; x += 0.35f) {
            const glm::vec3 base(x + r.range(0.0f, 0.35f), 0.0f, z + r.range(0.0f, 0.35f));
            const float turn = r.range(0.0f, kPi), scale = r.range(0.7f, 1.3f);
            for (int k = 0; k < 3; ++k) addCard(grass, base, turn + float(k) * kPi / 3.0f, 0.45f * scale, 0.4f * scale);
        }
    add(std::move(grass));

    // Leaves: the tree's crown (cards of 0.7 m with random orientation, denser towards the centre) and a hedge
    // 1.4 m high along the wall.
    TriangleMesh leaves = alphaTestedCards("leaves", leafTexture());
    for (int i = 0; i < 700; ++i) {
        const float z = r.range(-1.0f, 1.0f), phi = r.range(0.0f, 2.0f * kPi), radius = 1.7f * std::cbrt(r.next());
        const glm::vec3 dir(std::sqrt(1.0f - z * z) * std::cos(phi), z, std::sqrt(1.0f - z * z) * std::sin(phi));
        addRandomLeafCard(leaves, crown + dir * glm::vec3(1.0f, 0.8f, 1.0f) * radius, 0.7f, r);
    }
    for (int i = 0; i < 1200; ++i) {
        const glm::vec3 centre(r.range(-9.5f, 9.5f), r.range(0.2f, 1.3f), r.range(-6.8f, -6.0f));
        addRandomLeafCard(leaves, centre, 0.6f, r);
    }
    add(std::move(leaves));

    s.environment.skyRadiance = glm::vec3(0.35f, 0.45f, 0.65f);
    s.environment.sunDirection = glm::normalize(glm::vec3(0.45f, 0.75f, 0.5f));
    s.environment.sunIrradiance = glm::vec3(4.0f);
    s.environment.sunAngle = 0.0093f;  // the real sun's disc: soft-edged leaf shadows
    // From the meadow's front edge, a little above the grass: grass below, the tree and the hedge before the wall.
    s.camera = {glm::vec3(0.0f, 1.7f, 5.5f), glm::vec3(0.8f, 0.9f, -4.0f), glm::vec3(0, 1, 0), 60.0f};
    s.computeBounds();
    return s;
}

}  // namespace bricklight::scenes
