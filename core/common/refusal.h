// How every technique refuses a call: the caller's Error (when given) gets the code and "<object>: <why>", and the
// call returns false, null or empty, whichever it returns (Refused converts to each), having changed nothing.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "bricklight/errors.h"

namespace bricklight::detail {

struct Refused {
    operator bool() const { return false; }
    template <class T>
    operator std::unique_ptr<T>() const { return nullptr; }
    template <class T>
    operator std::optional<T>() const { return std::nullopt; }
};

class Refusal {
public:
    Refusal(Error* error, const char* object) : error_(error), object_(object) {}
    Refused operator()(const std::string& why, ErrorCode code = ErrorCode::InvalidArgument) const {
        if (error_) *error_ = {code, std::string(object_) + ": " + why};
        return {};
    }

private:
    Error* error_;
    const char* object_;
};

}  // namespace bricklight::detail
