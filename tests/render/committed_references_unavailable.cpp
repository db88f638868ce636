// Without OpenImageIO the committed references cannot be read: every reference is traced (and cached).
#include "committed_references.h"

namespace bricklight::testing {

std::string committedReferenceDir() { return BRICKLIGHT_TEST_COMMITTED_REFERENCE_DIR; }
bool committedReferencesAvailable() { return false; }
std::string committedReferenceKey(const std::string&) { return ""; }
bool readCommittedReference(const std::string&, uint32_t, uint32_t, uint32_t, AovImages&) { return false; }
bool writeCommittedReference(const std::string&, const std::string&, const std::string&, uint32_t, const AovImages&, std::string* error) {
    *error = "this build reads and writes no image files (BRICKLIGHT_OPENIMAGEIO is off)";
    return false;
}

}  // namespace bricklight::testing
