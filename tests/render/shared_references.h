// The path-traced references the comparisons read, as recipes: each is committed under tests/references/
// (committed_references.h; scripts/update_test_references.sh traces them anew), so a fresh build tree reads
// instead of tracing. When a recipe's file is stale or missing, the test "path-traced references the comparisons
// share" traces it once per backend, and ctest runs it before the comparisons that read it (a fixture:
// tests/schedule/reference_fixtures.cmake), so that no comparison waits with a core idle while another traces the
// image it needs; the test "committed references are current" fails and names the file.
#pragma once

#include <string>
#include <vector>

#include "reference_cache.h"

namespace bricklight::testing {

constexpr uint32_t kSharedReferenceSize = 128;  // the Cornell comparisons' image size
constexpr uint32_t kSharedReferenceSpp = 512;

// The Cornell box with a glossy metal floor (metalness 1, roughness 0.3, albedo 0.9): GI's and voxel cone
// tracing's specular comparisons.
scenes::SceneGeometry glossyFloorCornell();

struct ReferenceRecipe {
    std::string name;  // tests/references/<name>.exr
    scenes::SceneGeometry scene;
    render::PathTracerOptions options;
    uint32_t spp = 0;
};

// Every committed reference's recipe.
std::vector<ReferenceRecipe> referenceRecipes();
ReferenceRecipe referenceRecipe(const std::string& name);  // fails the test if there is none of that name

Reference cornellReference(TestDevice& td);           // every bounce
Reference cornellOneBounceReference(TestDevice& td);  // maxBounces 1
Reference glossyFloorReference(TestDevice& td);
Reference foliageReference(TestDevice& td, bool sunBehindCards);  // foliage_test_support.h's scene, 64², 256 spp
Reference mirrorFloorReference(TestDevice& td, float roughness);   // cornellMirror(0.05 or 0.3), 1 bounce
Reference cornellGlassReference(TestDevice& td);
// The built-in corridor (single-sided walls, the lamp around a corner), kCorridorWidth × kCorridorHeight, 1024 spp.
constexpr uint32_t kCorridorWidth = 96, kCorridorHeight = 64;
Reference corridorReference(TestDevice& td);

}  // namespace bricklight::testing
