// The committed path-traced references (committed_references.h): every recipe's file is there and traced from
// today's content, each backend's path tracer still makes the image a file holds, and the hidden test that
// scripts/update_test_references.sh runs to trace them anew.
#include <cmath>
#include <filesystem>
#include <map>
#include <set>

#include "backend_test.h"
#include "committed_references.h"
#include "image_metrics.h"
#include "render_test_support.h"
#include "shared_references.h"

using namespace bricklight;
using namespace bricklight::testing;

namespace {

std::string committedPath(const ReferenceRecipe& recipe) { return committedReferenceDir() + "/" + recipe.name + ".exr"; }

// Fewer samples of the same sequence (the same seed: the first samples of the committed image's), to check a
// backend against a committed image at a sixteenth of its cost.
constexpr uint32_t kSampleDivisor = 16;

struct Agreement {
    double worstMeanError = 0.0;  // the largest relative difference of one AOV's mean
    std::string worstAov;
    double combinedRelMse = 0.0;
};

Agreement agreement(render::PathTracer& low, const AovImages& committed) {
    Agreement a;
    for (uint32_t i = 0; i < uint32_t(render::Aov::Count); ++i) {
        const render::Image mine = low.read(render::Aov(i));
        const double m = imageMean(mine), c = imageMean(committed[i]);
        const double error = std::fabs(m - c) / std::max(std::fabs(c), 1e-6);
        if (error > a.worstMeanError) {
            a.worstMeanError = error;
            a.worstAov = render::aovName(render::Aov(i));
        }
    }
    a.combinedRelMse = render::compareImages(low.read(render::Aov::Combined), committed[size_t(render::Aov::Combined)]).relMse;
    return a;
}

void reproducesCommitted(const std::string& backend) {
    if (!committedReferencesAvailable()) {
        WARN("this build reads no image files: the references are traced, none is committed");
        return;
    }
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    std::map<std::string, AovImages> committed;
    for (const ReferenceRecipe& recipe : referenceRecipes()) {
        INFO(recipe.name);
        REQUIRE(readCommittedReference(portableReferenceKey(recipe.scene, recipe.options, recipe.spp), recipe.options.width,
                                       recipe.options.height, recipe.spp, committed[recipe.name]));
    }
    for (const ReferenceRecipe& recipe : referenceRecipes()) {
        std::string error;
        auto pt = render::PathTracer::create(*td.device, recipe.scene, recipe.options, &error);
        INFO(recipe.name << ": " << error);
        REQUIRE(pt);
        pt->addSamples(recipe.spp / kSampleDivisor);
        const Agreement a = agreement(*pt, committed[recipe.name]);
        WARN(backend << ": " << recipe.name << " at " << recipe.spp / kSampleDivisor << " spp against the committed " << recipe.spp
                     << ": worst AOV mean off by " << a.worstMeanError << " (" << a.worstAov << "), combined relMSE " << a.combinedRelMse);
        // Measured on both backends (the two agree to 1e-4): the worst AOV mean off by 0.0116 (the glossy floor's
        // indirect diffuse), the combined relMSE at most 0.087 (the near-mirror floor's highlights at 32 spp).
        // Bounds: about two and a half times those. The first sixteenth of the same sample sequence agrees with
        // the whole far closer than an independent trace would.
        CHECK(a.worstMeanError < 0.03);
        CHECK(a.combinedRelMse < 0.2);
        // Teeth: against another recipe's file of the same size (Cornell against its one-bounce image: the light
        // of the second and later bounces missing) the same check fails (measured: the indirect diffuse mean off by 0.98).
        if (recipe.name == "cornell") {
            const Agreement wrong = agreement(*pt, committed["cornell-one-bounce"]);
            WARN("cornell against the one-bounce file: worst AOV mean off by " << wrong.worstMeanError << " (" << wrong.worstAov << ")");
            CHECK(wrong.worstMeanError > 0.1);
        }
    }
    REQUIRE_NO_MESSAGES(td);
}

}  // namespace

TEST_CASE("committed references are current: one file per recipe, traced from today's content", "[references]") {
    if (!committedReferencesAvailable()) {
        WARN("this build reads no image files: the references are traced, none is committed");
        return;
    }
    std::set<std::string> expected;
    for (const ReferenceRecipe& recipe : referenceRecipes()) {
        const std::string path = committedPath(recipe);
        expected.insert(std::filesystem::path(path).filename().string());
        INFO(path << " is missing or was traced from other content (the scene, the options, the path tracer's code or shaders "
                     "changed): run scripts/update_test_references.sh and commit tests/references/");
        CHECK(committedReferenceKey(path) == portableReferenceKey(recipe.scene, recipe.options, recipe.spp));
    }
    for (const auto& entry : std::filesystem::directory_iterator(committedReferenceDir())) {
        INFO(entry.path().string() << " belongs to no recipe (shared_references.cpp): run scripts/update_test_references.sh");
        CHECK((entry.path().filename() == "README.md" || expected.count(entry.path().filename().string()) == 1));
    }
}

// Hidden: scripts/update_test_references.sh runs it by name. Traces every recipe on Vulkan (or reads what this
// build tree's cache holds of the same content) and writes tests/references/<name>.exr, removing files of no
// recipe.
TEST_CASE("update the committed references", "[.update-references]") {
    REQUIRE(committedReferencesAvailable());
    TestDevice td = makeDevice("vulkan");
    REQUIRE(td.device);
    std::set<std::string> written;
    for (const ReferenceRecipe& recipe : referenceRecipes()) {
        const std::string path = committedPath(recipe);
        const std::string key = portableReferenceKey(recipe.scene, recipe.options, recipe.spp);
        if (committedReferenceKey(path) == key) {
            WARN(path << ": current");
        } else {
            const Reference r = pathTraced(td, recipe.scene, recipe.options, recipe.spp);
            AovImages aovs;
            for (size_t a = 0; a < aovs.size(); ++a) aovs[a] = r.read(render::Aov(a));
            std::string error;
            INFO(error);
            REQUIRE(writeCommittedReference(path, key, recipe.name, recipe.spp, aovs, &error));
            WARN(path << ": written (" << recipe.spp << " spp)");
        }
        written.insert(std::filesystem::path(path).filename().string());
    }
    for (const auto& entry : std::filesystem::directory_iterator(committedReferenceDir()))
        if (entry.path().extension() == ".exr" && !written.count(entry.path().filename().string())) {
            WARN(entry.path().string() << ": removed (no recipe)");
            std::filesystem::remove(entry.path());
        }
    REQUIRE_NO_MESSAGES(td);
}

BACKEND_TEST("the path tracer reproduces the committed references", "[render]", reproducesCommitted)

// Traces the shared references that are stale or missing, before the comparisons that read them (a fixture:
// tests/schedule/reference_fixtures.cmake).
static void traceSharedReferences(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    for (const ReferenceRecipe& recipe : referenceRecipes()) {
        INFO(recipe.name);
        const Reference r = pathTraced(td, recipe.scene, recipe.options, recipe.spp);
        REQUIRE(r.read(render::Aov::Combined).width == recipe.options.width);
        CHECK(imageMean(r.read(render::Aov::Combined)) > 0.0);
    }
    REQUIRE_NO_MESSAGES(td);
}

BACKEND_TEST("path-traced references the comparisons share", "[render]", traceSharedReferences)
