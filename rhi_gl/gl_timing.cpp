#include "gl_timing.h"

namespace bricklight::gl::detail {

GLuint MarkerTimer::query(const Functions& gl) {
    if (!free_.empty()) {
        GLuint q = free_.back();
        free_.pop_back();
        return q;
    }
    GLuint q = 0;
    gl.GenQueries(1, &q);
    return q;
}

size_t MarkerTimer::begin(const Functions& gl, std::string label, uint64_t frame) {
    Pair p;
    p.label = std::move(label);
    p.frame = frame;
    p.begin = query(gl);
    p.end = query(gl);
    gl.QueryCounter(p.begin, GL_TIMESTAMP);
    pairs_.push_back(std::move(p));
    return indexBase_ + pairs_.size() - 1;
}

void MarkerTimer::end(const Functions& gl, size_t index) {
    if (index < indexBase_ || index - indexBase_ >= pairs_.size()) return;
    Pair& p = pairs_[index - indexBase_];
    gl.QueryCounter(p.end, GL_TIMESTAMP);
    p.ended = true;
}

std::vector<rhi::MarkerTiming> MarkerTimer::take(const Functions& gl) {
    std::vector<rhi::MarkerTiming> out;
    for (Pair& p : pairs_) {
        if (!p.ended || p.done) continue;
        GLint available = 0;
        gl.GetQueryObjectiv(p.end, GL_QUERY_RESULT_AVAILABLE, &available);
        if (!available) continue;
        gl.GetQueryObjectiv(p.begin, GL_QUERY_RESULT_AVAILABLE, &available);
        if (!available) continue;
        GLuint64 t0 = 0, t1 = 0;
        gl.GetQueryObjectui64v(p.begin, GL_QUERY_RESULT, &t0);
        gl.GetQueryObjectui64v(p.end, GL_QUERY_RESULT, &t1);
        out.push_back({p.label, t1 > t0 ? double(t1 - t0) / 1e6 : 0.0, p.frame});
        p.done = true;
    }
    // Pop collected pairs from the front only: open markers keep the indices handed out by begin().
    size_t n = 0;
    while (n < pairs_.size() && pairs_[n].done) {
        free_.push_back(pairs_[n].begin);
        free_.push_back(pairs_[n].end);
        ++n;
    }
    if (n) {
        pairs_.erase(pairs_.begin(), pairs_.begin() + n);
        indexBase_ += n;
    }
    return out;
}

void MarkerTimer::destroy(const Functions& gl) {
    for (Pair& p : pairs_) {
        gl.DeleteQueries(1, &p.begin);
        gl.DeleteQueries(1, &p.end);
    }
    if (!free_.empty()) gl.DeleteQueries(GLsizei(free_.size()), free_.data());
    pairs_.clear();
    free_.clear();
}

}  // namespace bricklight::gl::detail
