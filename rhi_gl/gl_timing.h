// GPU timing of markers: a GL_TIMESTAMP query at begin and at end of each timed marker; takeTimings()
// collects the pairs whose results are available (GL_QUERY_RESULT_AVAILABLE), never waiting.
#pragma once

#include <string>
#include <vector>

#include "bricklight/rhi.h"
#include "gl_functions.h"

namespace bricklight::gl::detail {

class MarkerTimer {
public:
    // Returns an index for end(); call only when timestamps are supported.
    size_t begin(const Functions& gl, std::string label, uint64_t frame);
    void end(const Functions& gl, size_t index);
    std::vector<rhi::MarkerTiming> take(const Functions& gl);
    void destroy(const Functions& gl);

private:
    struct Pair {
        std::string label;
        uint64_t frame = 0;
        GLuint begin = 0, end = 0;
        bool ended = false;
        bool done = false;  // collected: slot free for reuse once the front is popped
    };
    GLuint query(const Functions& gl);
    std::vector<Pair> pairs_;  // begin order
    std::vector<GLuint> free_;
    size_t indexBase_ = 0;  // absolute index of pairs_[0]
};

}  // namespace bricklight::gl::detail
