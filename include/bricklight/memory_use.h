// What a technique object holds on the device, resource by resource: every technique's memoryUse() answers with
// this, so that an application can add up and budget its GI the same way whatever it uses.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace bricklight {

struct MemoryUse {
    struct Resource {
        std::string name;
        uint64_t bytes = 0;
    };
    std::vector<Resource> resources;
    uint64_t totalBytes = 0;
};

}  // namespace bricklight
