// Path-traced references, paid for once per build tree: the renderer tests compare the fast path, GI and voxel
// cone tracing against the same few converged path-traced images, so each is traced once and kept under
// BRICKLIGHT_TEST_REFERENCE_DIR (in the build tree), shared by every test program and safe under parallel ctest.
//
// The key is the content, not a name: the path tracer's creation and its samples are recorded on a null
// device (every buffer and texture it uploads, every dispatch and its constants) and hashed together with the
// code of every shader it creates, the backend and the device. Any change to the scene, the options, the
// sample count, the path tracer's C++ or its shaders gives a new key, so a cached image is never stale. The
// references the comparisons share are also committed (committed_references.h): a fresh build tree reads them
// instead of tracing. docs/notes/test-suite.md says why both.
//
// BRICKLIGHT_TEST_REFERENCE_CACHE=0 traces every reference anew (nothing read or written).
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "backend_test.h"
#include "path_tracer.h"

namespace bricklight::testing {

// Every AOV of one path-traced image (what PathTracer::read gives after the samples).
class Reference {
public:
    const render::Image& read(render::Aov aov) const { return aovs_[size_t(aov)]; }
    uint32_t samples() const { return samples_; }
    bool fromCache() const { return fromCache_; }          // this build tree's cache
    bool fromCommitted() const { return fromCommitted_; }  // tests/references (committed_references.h)

private:
    friend Reference pathTraced(TestDevice&, const scenes::SceneGeometry&, const render::PathTracerOptions&, uint32_t);
    std::array<render::Image, size_t(render::Aov::Count)> aovs_;
    uint32_t samples_ = 0;
    bool fromCache_ = false;
    bool fromCommitted_ = false;
};

// The path tracer's image of `scene` with `options` after `spp` samples per pixel on `td`'s backend: read from
// the cache when an earlier test (of any program) traced the same, else from the committed file traced from the
// same content (committed_references.h), otherwise traced now and stored. Two
// processes that want the same image at once trace it once: the second waits for the first's file.
Reference pathTraced(TestDevice& td, const scenes::SceneGeometry& scene, const render::PathTracerOptions& options, uint32_t spp);

// The content key of that image (hex), for tests of the cache itself.
std::string referenceKey(TestDevice& td, const scenes::SceneGeometry& scene, const render::PathTracerOptions& options, uint32_t spp);

// The key without the backend and the device (nor the SPIR-V, which the GL source determines): the same answer
// traced anywhere. Committed references carry it: one file serves both backends, and the test "the path tracer
// reproduces the committed references" checks each backend's trace against it.
std::string portableReferenceKey(const scenes::SceneGeometry& scene, const render::PathTracerOptions& options, uint32_t spp);

// The shorthand the tests use (as render_test_support.h's traced()): a square image, pixel jitter, seed and
// bounce limit given.
Reference pathTraced(TestDevice& td, const scenes::SceneGeometry& scene, uint32_t size, uint32_t spp, bool jitter = true,
                     uint32_t seed = 1, uint32_t maxBounces = render::PathTracerOptions{}.maxBounces);

}  // namespace bricklight::testing
