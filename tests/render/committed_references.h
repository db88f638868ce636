// Path-traced references committed under tests/references/: OpenEXR files, one per recipe in
// shared_references.cpp, each carrying the content key it was traced from (reference_cache.h's portable key:
// the scene, the options, the sample count and the path tracer's C++ and shaders, not the backend or device).
// A reference whose key matches a committed file is read from it instead of traced; a stale file is never read
// (its key no longer matches) and the test "committed references are current" names it.
// scripts/update_test_references.sh traces them anew. docs/notes/test-suite.md says why both this and the cache.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "path_tracer.h"

namespace bricklight::testing {

using AovImages = std::array<render::Image, size_t(render::Aov::Count)>;

// Where the committed files are (the source tree's tests/references).
std::string committedReferenceDir();

// False when this build reads no image files (BRICKLIGHT_OPENIMAGEIO off): every reference is traced.
bool committedReferencesAvailable();

// The key a committed file was traced from ("" if `path` is not a readable reference file).
std::string committedReferenceKey(const std::string& path);

// The committed file with `key`, read into `aovs` (all of them `width` x `height`, traced with `spp` samples).
// False if no file in committedReferenceDir() has that key.
bool readCommittedReference(const std::string& key, uint32_t width, uint32_t height, uint32_t spp, AovImages& aovs);

// Writes `aovs` to `path` with `key`, the recipe's `name` and `spp` in its header. False with `error` set.
bool writeCommittedReference(const std::string& path, const std::string& key, const std::string& name, uint32_t spp,
                             const AovImages& aovs, std::string* error);

}  // namespace bricklight::testing
