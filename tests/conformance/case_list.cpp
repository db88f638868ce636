// cases(): every file's cases, sorted by name so that the order (and the runner's output) does not depend
// on the order of the files.
#include <algorithm>
#include <cstring>

#include "case_lists.h"

namespace bricklight::conformance {

const std::vector<Case>& cases() {
    static const std::vector<Case> all = [] {
        std::vector<Case> c;
        appendComputeCases(c);
        appendDrawCases(c);
        appendFormatCases(c);
        appendHazardCases(c);
        appendIndirectCases(c);
        appendSamplerCases(c);
        appendTransferCases(c);
        appendViewCases(c);
        std::sort(c.begin(), c.end(), [](const Case& a, const Case& b) { return std::strcmp(a.name, b.name) < 0; });
        return c;
    }();
    return all;
}

}  // namespace bricklight::conformance
