// The path-traced references several comparisons share. The test "path-traced references the comparisons share"
// traces them once per backend, and ctest runs it before the comparisons that read them (a fixture:
// tests/schedule/reference_fixtures.cmake), so that no comparison waits with a core idle while another traces the
// image it needs. Run alone, a comparison traces (or reads) the image itself: reference_cache.h.
#pragma once

#include "reference_cache.h"

namespace bricklight::testing {

constexpr uint32_t kSharedReferenceSize = 128;  // the Cornell comparisons' image size
constexpr uint32_t kSharedReferenceSpp = 512;

// The Cornell box with a glossy metal floor (metalness 1, roughness 0.3, albedo 0.9): GI's and voxel cone
// tracing's specular comparisons.
scenes::SceneGeometry glossyFloorCornell();

Reference cornellReference(TestDevice& td);           // every bounce
Reference cornellOneBounceReference(TestDevice& td);  // maxBounces 1
Reference glossyFloorReference(TestDevice& td);

}  // namespace bricklight::testing
