// What went wrong, the same for every technique: a call that refuses its input returns false (or null) and says
// why in an Error — a stable ErrorCode for code that branches on it, and a message for people that names the
// object and the problem — and changes nothing. The long-lived scene objects (sdf::SdfScene, gi::GiContext) also
// keep their last Error and collect Diagnostics: each distinct message once with a count, so that a mistake
// repeated every frame reaches the application's callback once and stays countable.
#pragma once

#include <cstdint>
#include <string>

#include "bricklight/rhi.h"

namespace bricklight {

// Stable: values are never renumbered; new ones are added at the end.
enum class ErrorCode : uint16_t {
    None = 0,
    InvalidArgument = 1,      // a description field or parameter out of range, not finite or inconsistent
    InvalidHandle = 2,        // a handle that is null where one is needed, unknown, or already destroyed
    MissingInput = 3,         // a required input or output is not given (or one that another needs)
    WrongFormat = 4,          // a texture or buffer of the wrong format, channel count, dimension or usage
    WrongSize = 5,            // a texture of the wrong size
    Aliasing = 6,             // one resource given as an input and as an output
    Unsupported = 7,          // the device lacks a format, feature or limit; a shader is not linked in
    OverBudget = 8,           // a capacity, budget or fixed maximum exceeded
    InvalidGeometry = 9,      // empty meshes, NaN/inf positions, indices out of range
    InUse = 10,               // the object is still used by another (a mesh by instances)
    DependencyDestroyed = 11, // an object this one follows was destroyed first (the scene of a GI context)
    DeviceFailure = 12,       // the device refused to create or do something (see the device's messages)
    InvalidState = 13,        // a call made before what it needs (a debug view before the first dispatch)
    CameraMismatch = 14,      // warning: positions rebuilt from depth disagree with the distance field
    SceneNotUpdated = 15,     // warning: GI dispatched on a scene that was never update()d
};
const char* errorCodeName(ErrorCode code);  // "InvalidArgument", ...

// Every technique's create() and calls take an optional Error* (null: the caller does not want the details).
struct Error {
    ErrorCode code = ErrorCode::None;
    std::string message;  // "<object>: <problem>", "" when code is None
};

// One distinct message of an object (its first report), how often it was reported, and its code.
struct Diagnostic {
    ErrorCode code = ErrorCode::None;
    rhi::Severity severity = rhi::Severity::Error;
    std::string message;
    uint64_t count = 0;
};

}  // namespace bricklight
