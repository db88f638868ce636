// The path tracer's ambient-occlusion AOV (the reference for voxel AO): open wherever the range is too short
// to reach anything, darker where the Cornell box's floor meets its walls than on open floor, 1 where the
// camera ray escapes, brighter as the range shrinks; and its option's validation.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "backend_test.h"
#include "path_tracer.h"
#include "render_test_support.h"

using namespace bricklight;
using namespace bricklight::testing;

namespace {

constexpr uint32_t kSize = 64;

// Cornell's box is about 556 units wide: its bounding box's diagonal, for ranges relative to the scene.
float diagonalOf(const scenes::SceneGeometry& s) { return glm::length(s.boundsMax - s.boundsMin); }

// AO depends only on the primary hit, not on the path behind it: one bounce keeps the tests quick.
std::unique_ptr<render::PathTracer> aoTraced(TestDevice& td, const scenes::SceneGeometry& scene, float range, uint32_t spp,
                                             bool jitter = true) {
    render::PathTracerOptions o;
    o.width = o.height = kSize;
    o.maxBounces = 1;
    o.pixelJitter = jitter;
    o.aoRange = range;
    std::string error;
    auto pt = render::PathTracer::create(*td.device, scene, o, &error);
    INFO(error);
    REQUIRE(pt);
    pt->addSamples(spp);
    return pt;
}

double meanOf(const render::Image& img) {
    double sum = 0.0;
    for (size_t p = 0; p < size_t(img.width) * img.height; ++p) sum += img.rgb[3 * p];
    return sum / double(size_t(img.width) * img.height);
}

// Every pixel's three channels equal and in [0, 1].
bool wellFormed(const render::Image& ao) {
    for (size_t p = 0; p < size_t(ao.width) * ao.height; ++p) {
        const float r = ao.rgb[3 * p], g = ao.rgb[3 * p + 1], b = ao.rgb[3 * p + 2];
        if (!(r >= 0.0f && r <= 1.0f) || r != g || r != b) return false;
    }
    return true;
}

// The world point that pixel (x, y)'s centre ray reaches at view depth `depth` (as path_trace.comp casts it;
// exact with pixel jitter off).
glm::vec3 primaryHit(const scenes::Camera& c, uint32_t x, uint32_t y, float depth) {
    const glm::vec3 forward = glm::normalize(c.at - c.eye), right = glm::normalize(glm::cross(forward, c.up));
    const glm::vec3 up = glm::cross(right, forward);
    const float tanHalf = std::tan(glm::radians(c.verticalFovDegrees) * 0.5f);
    const glm::vec2 ndc = (glm::vec2(x, y) + 0.5f) / float(kSize) * 2.0f - 1.0f;
    const glm::vec3 dir = glm::normalize(forward + right * (ndc.x * tanHalf) - up * (ndc.y * tanHalf));
    return c.eye + dir * (depth / glm::dot(dir, forward));
}

// Distance in the floor plane (x, z) from q to the segment ab.
float segmentDistance(glm::vec2 q, glm::vec2 a, glm::vec2 b) {
    const glm::vec2 ab = b - a;
    const float t = glm::clamp(glm::dot(q - a, ab) / glm::max(glm::dot(ab, ab), 1e-12f), 0.0f, 1.0f);
    return glm::length(q - (a + t * ab));
}

// The floor-level outline of the named meshes: segments between their vertices at y = 0 (for a convex
// block, its footprint's edges and diagonals; the nearest of them to a point outside is on the outline).
std::vector<std::pair<glm::vec2, glm::vec2>> floorOutline(const scenes::SceneGeometry& s, std::initializer_list<const char*> names) {
    std::vector<std::pair<glm::vec2, glm::vec2>> segments;
    for (const char* name : names)
        for (const scenes::TriangleMesh& m : s.meshes) {
            if (m.name != name) continue;
            std::vector<glm::vec2> base;
            for (size_t i = 0; i + 2 < m.positions.size(); i += 3)
                if (m.positions[i + 1] == 0.0f) {
                    const glm::vec2 v(m.positions[i], m.positions[i + 2]);
                    if (std::find(base.begin(), base.end(), v) == base.end()) base.push_back(v);
                }
            for (size_t i = 0; i < base.size(); ++i)
                for (size_t j = i + 1; j < base.size(); ++j) segments.push_back({base[i], base[j]});
        }
    return segments;
}

float distanceTo(glm::vec2 q, const std::vector<std::pair<glm::vec2, glm::vec2>>& segments) {
    float d = INFINITY;
    for (const auto& [a, b] : segments) d = std::min(d, segmentDistance(q, a, b));
    return d;
}

void tinyRangeIsOpen(const std::string& backend) {
    // With a range of 1e-4 of the scene (10 times the ray offset) almost no ray reaches anything: only the
    // pixels on a floor/wall edge lose a little. Measured mean over the geometry 0.99987 (Vulkan and GL).
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    const scenes::SceneGeometry cornell = scenes::cornellBox();
    auto pt = aoTraced(td, cornell, 1e-4f * diagonalOf(cornell), 16);
    const render::Image ao = pt->read(render::Aov::Ao), depth = pt->read(render::Aov::Depth);
    double sum = 0.0;
    size_t geometry = 0;
    for (size_t p = 0; p < size_t(kSize) * kSize; ++p)
        if (depth.rgb[3 * p] > 0.0f) sum += ao.rgb[3 * p], ++geometry;
    REQUIRE(geometry > size_t(kSize) * kSize / 2);
    const double mean = sum / double(geometry);
    INFO("mean AO over " << geometry << " pixels of geometry: " << mean);
    WARN("ao tiny range " << backend << ": " << mean);
    CHECK(wellFormed(ao));
    CHECK(mean > 0.995);
    REQUIRE_NO_MESSAGES(td);
}

void wallBesideFloorMatchesTheAnalyticAnswer(const std::string& backend) {
    // A floor point at distance d from a wall standing on it (both reaching past the range R everywhere in
    // view): a cosine-weighted direction, projected on the floor, is uniform over the unit disk (Malley), and
    // it meets the wall within R exactly when its component towards the wall is at least u = d / R. So
    // AO = 1 - (acos(u) - u sqrt(1 - u^2)) / pi for u < 1 (0.5 at the wall's foot), 1 beyond. 256 samples
    // per pixel: a pixel's AO is within about 0.03 (one sigma); means over bins of u of 0.1 (one or two
    // pixel columns, 64 or 128 pixels) within 0.004. Bound 0.015 per bin, 0.005 over the whole floor. Measured (Vulkan and GL alike): worst bin
    // 0.0047 (u in [0.3, 0.4): 0.7137 against 0.7184), mean error -0.0003; 0.532 against 0.534 at the foot.
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    const float range = 1.0f;
    scenes::SceneGeometry s;
    s.meshes.push_back(groundPlane(20.0f, glm::vec3(0.5f)));
    scenes::TriangleMesh wall;  // the plane x = 0, 20 high and 40 long (its side towards the floor point counts)
    wall.name = "wall";
    wall.positions = {0, 0, -20, 0, 0, 20, 0, 20, 20, 0, 20, -20};
    wall.indices = {0, 1, 2, 0, 2, 3};
    wall.albedo = glm::vec3(0.5f);
    s.meshes.push_back(wall);
    s.instances = {{0, glm::mat4(1.0f)}, {1, glm::mat4(1.0f)}};
    s.camera = {glm::vec3(1.0f, 3.0f, 0.0f), glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(0, 0, 1), 60.0f};  // down at the wall's foot
    s.computeBounds();
    auto pt = aoTraced(td, s, range, 256, false);
    const render::Image ao = pt->read(render::Aov::Ao), depth = pt->read(render::Aov::Depth);
    const render::Image normal = pt->read(render::Aov::Normal);
    CHECK(wellFormed(ao));
    double binSum[11] = {}, binExpected[11] = {}, errorSum = 0.0;
    size_t binCount[11] = {}, floor = 0;
    for (uint32_t y = 0; y < kSize; ++y)
        for (uint32_t x = 0; x < kSize; ++x) {
            const size_t p = size_t(y) * kSize + x;
            if (depth.rgb[3 * p] <= 0.0f || normal.rgb[3 * p + 1] < 0.999f) continue;  // the wall
            const double u = primaryHit(s.camera, x, y, depth.rgb[3 * p]).x / range;
            const double expected = u < 1.0 ? 1.0 - (std::acos(u) - u * std::sqrt(1.0 - u * u)) / M_PI : 1.0;
            const int bin = std::min(int(u * 10.0), 10);
            binSum[bin] += ao.rgb[3 * p];
            binExpected[bin] += expected;
            ++binCount[bin];
            errorSum += ao.rgb[3 * p] - expected;
            ++floor;
        }
    REQUIRE(floor > size_t(kSize) * kSize / 2);
    const double meanError = errorSum / double(floor);
    std::ostringstream table;
    double worst = 0.0;
    for (int b = 0; b < 11; ++b) {
        REQUIRE(binCount[b] >= 50);
        const double measured = binSum[b] / double(binCount[b]), expected = binExpected[b] / double(binCount[b]);
        worst = std::max(worst, std::fabs(measured - expected));
        table << " " << measured << "/" << expected << " (" << binCount[b] << ")";
    }
    INFO("AO measured/expected by u = d / R in tenths (the last: u >= 1):" << table.str() << "; mean error " << meanError);
    WARN("ao analytic " << backend << ": worst bin " << worst << ", mean error " << meanError << ";" << table.str());
    CHECK(worst < 0.015);
    CHECK(std::fabs(meanError) < 0.005);
    REQUIRE_NO_MESSAGES(td);
}

void cornellCornersAreDark(const std::string& backend) {
    // Range a quarter of the box. Pixel centres only (no jitter), so that each pixel's AO belongs to the
    // one floor point its depth gives. Floor pixels within 0.1 x range of a wall (the floor/wall edges)
    // against open floor: pixels at least 0.7 x range from every wall and block, whose hemisphere loses at
    // most a sliver to far occluders. Measured (64 spp, Vulkan and GL alike): edges 0.518 (35 pixels; about
    // 0.5 expected at a wall's foot, a little more away from it), open floor 0.979 (56 pixels), image mean
    // 0.820, and the 252 pixels past the box's open front exactly 1.
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    const scenes::SceneGeometry cornell = scenes::cornellBox();
    const float range = 0.25f * 556.0f;
    auto pt = aoTraced(td, cornell, range, 64, false);
    CHECK(pt->aoRange() == range);
    const render::Image ao = pt->read(render::Aov::Ao), depth = pt->read(render::Aov::Depth);
    const render::Image normal = pt->read(render::Aov::Normal);
    CHECK(wellFormed(ao));

    const auto walls = floorOutline(cornell, {"back wall", "red wall", "green wall"});
    const auto blocks = floorOutline(cornell, {"short block", "tall block"});
    REQUIRE(walls.size() == 3);    // one floor edge per wall
    REQUIRE(blocks.size() == 12);  // 4 corners per block: 4 edges and 2 diagonals
    double edgeSum = 0.0, openSum = 0.0, skyWorst = 1.0;
    size_t edgeCount = 0, openCount = 0, skyCount = 0;
    for (uint32_t y = 0; y < kSize; ++y)
        for (uint32_t x = 0; x < kSize; ++x) {
            const size_t p = size_t(y) * kSize + x;
            const float a = ao.rgb[3 * p];
            if (depth.rgb[3 * p] <= 0.0f) {  // the camera ray escaped (past the box's open front)
                skyWorst = std::min(skyWorst, double(a));
                ++skyCount;
                continue;
            }
            if (normal.rgb[3 * p + 1] < 0.999f) continue;  // not the floor
            const glm::vec3 hit = primaryHit(cornell.camera, x, y, depth.rgb[3 * p]);
            if (std::fabs(hit.y) > 1.0f) continue;  // a block's top
            const glm::vec2 q(hit.x, hit.z);
            const float wall = distanceTo(q, walls), block = distanceTo(q, blocks);
            if (wall < 0.1f * range) edgeSum += a, ++edgeCount;
            if (std::min(wall, block) > 0.7f * range) openSum += a, ++openCount;
        }
    REQUIRE(edgeCount >= 10);
    REQUIRE(openCount >= 10);
    const double edge = edgeSum / double(edgeCount), open = openSum / double(openCount), mean = meanOf(ao);
    INFO("floor/wall edges " << edge << " (" << edgeCount << " pixels), open floor " << open << " (" << openCount
                             << " pixels), image mean " << mean << ", sky " << skyCount << " pixels, lowest " << skyWorst);
    WARN("ao cornell " << backend << ": edges " << edge << " (" << edgeCount << "), open " << open << " (" << openCount
                       << "), mean " << mean << ", sky " << skyCount << " min " << skyWorst);
    CHECK(edge < open - 0.25);
    CHECK(edge > 0.4);
    CHECK(edge < 0.65);
    CHECK(open > 0.93);
    CHECK(mean > 0.72);
    CHECK(mean < 0.92);
    CHECK(skyWorst == 1.0);
    REQUIRE_NO_MESSAGES(td);
}

void aoGrowsAsTheRangeShrinks(const std::string& backend) {
    // The same pixels and sample directions at three ranges: a shorter range can only lose hits, so the
    // mean grows (per sample, not only on average). Measured at 16 spp (Vulkan and GL alike): 0.711, 0.904,
    // 0.974; the bound asks for steps of 0.02 at least.
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    const scenes::SceneGeometry cornell = scenes::cornellBox();
    double means[3];
    const float fractions[3] = {0.4f, 0.15f, 0.04f};
    for (int i = 0; i < 3; ++i) means[i] = meanOf(aoTraced(td, cornell, fractions[i] * 556.0f, 16)->read(render::Aov::Ao));
    INFO("mean AO at range 0.4, 0.15, 0.04 x box: " << means[0] << ", " << means[1] << ", " << means[2]);
    WARN("ao ranges " << backend << ": " << means[0] << ", " << means[1] << ", " << means[2]);
    CHECK(means[0] + 0.02 < means[1]);
    CHECK(means[1] + 0.02 < means[2]);
    REQUIRE_NO_MESSAGES(td);
}

void aoRangeIsChecked(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    const scenes::SceneGeometry cornell = scenes::cornellBox();
    render::PathTracerOptions o;
    o.width = o.height = 8;
    std::string error;
    for (float bad : {-1.0f, NAN, INFINITY}) {
        o.aoRange = bad;
        error.clear();
        CHECK(!render::PathTracer::create(*td.device, cornell, o, &error));
        INFO(error);
        CHECK(error.find("aoRange") != std::string::npos);
    }
    o.aoRange = 0.0f;  // the default: a tenth of the scene's diagonal
    auto pt = render::PathTracer::create(*td.device, cornell, o, &error);
    REQUIRE(pt);
    CHECK(pt->aoRange() == Approx(0.1 * diagonalOf(cornell)).epsilon(1e-5));
    render::Aov aov = render::Aov::Combined;
    CHECK(render::aovFromName("ao", &aov));
    CHECK(aov == render::Aov::Ao);
    CHECK(std::string(render::aovName(render::Aov::Ao)) == "ao");
    REQUIRE_NO_MESSAGES(td);
}

}  // namespace

BACKEND_TEST("path tracer ao: a tiny range leaves everything open", "[render][ao]", tinyRangeIsOpen)
BACKEND_TEST("path tracer ao: a wall beside a floor matches the analytic answer", "[render][ao]", wallBesideFloorMatchesTheAnalyticAnswer)
BACKEND_TEST("path tracer ao: cornell's floor/wall edges are darker than open floor", "[render][ao]", cornellCornersAreDark)
BACKEND_TEST("path tracer ao: the mean grows as the range shrinks", "[render][ao]", aoGrowsAsTheRangeShrinks)
BACKEND_TEST("path tracer ao: the range is checked and defaults to a tenth of the diagonal", "[render][ao]", aoRangeIsChecked)
