// The hostile-size test body (hostile_sizes.cpp) runs in both smoke programs against the bare backend, with
// no validation wrapper in front: each program supplies its backend through makeHostileBackend().
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "bricklight/rhi.h"

namespace smoke {

class HostileBackend {
public:
    virtual ~HostileBackend() = default;
    virtual const char* name() const = 0;
    virtual bricklight::rhi::IDevice& device() = 0;
    // The errors the backend reported since the last call.
    virtual std::vector<std::string> takeErrors() = 0;
    // What the layer below reported since the last call: Vulkan validation-layer messages, GL debug-output
    // errors. Every hostile call must be refused by the backend before it reaches that layer.
    virtual std::vector<std::string> takeDriverMessages() = 0;
};

std::unique_ptr<HostileBackend> makeHostileBackend();

}  // namespace smoke
