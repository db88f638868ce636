#include "reference_cache.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include "bricklight/rhi_validation.h"
#include "committed_references.h"
#include "bricklight/shader_blob.h"

namespace bricklight::testing {

namespace {

constexpr char kMagic[8] = {'B', 'L', 'R', 'E', 'F', '0', '1', '\0'};

// Two 64-bit FNV-1a hashes with different starting points: 128 bits of key, far beyond any chance collision
// among the few dozen images a suite keeps.
struct Hash128 {
    uint64_t a = 14695981039346656037ull, b = 0x9e3779b97f4a7c15ull;
    void add(const void* data, size_t size) {
        const auto* p = static_cast<const unsigned char*>(data);
        for (size_t i = 0; i < size; ++i) {
            a = (a ^ p[i]) * 1099511628211ull;
            b = (b ^ p[i]) * 0x100000001b3ull ^ (b >> 29);
        }
    }
    void add(const std::string& s) {
        const uint64_t n = s.size();
        add(&n, sizeof n);
        add(s.data(), s.size());
    }
    std::string hex() const {
        char text[33];
        std::snprintf(text, sizeof text, "%016llx%016llx", (unsigned long long)a, (unsigned long long)b);
        return text;
    }
};

bool cacheEnabled() {
    const char* v = std::getenv("BRICKLIGHT_TEST_REFERENCE_CACHE");
    return !(v && std::strcmp(v, "0") == 0);
}

// Every shader blob the recording names ("createShader" lines carry the blob's name): its GL source (and, for
// the cache's key, its SPIR-V) go into the key, so an edited shader never meets an image traced with the old one.
void addShaders(Hash128& h, const std::string& recording, bool withSpirv) {
    const std::string marker = "\"blob\":\"";
    for (size_t at = recording.find(marker); at != std::string::npos; at = recording.find(marker, at + 1)) {
        const size_t start = at + marker.size(), end = recording.find('"', start);
        const std::string name = recording.substr(start, end - start);
        const rhi::ShaderBlob* blob = rhi::findShader(name.c_str());
        h.add(name);
        if (!blob) continue;
        h.add(blob->glsl ? std::string(blob->glsl) : std::string());
        if (withSpirv) h.add(blob->spirv, blob->spirvWords * sizeof(uint32_t));
    }
}

bool readFile(const std::string& path, const render::PathTracerOptions& o, uint32_t spp,
              std::array<render::Image, size_t(render::Aov::Count)>& aovs) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return false;
    char magic[8];
    uint32_t header[4];
    if (!in.read(magic, sizeof magic) || std::memcmp(magic, kMagic, sizeof magic) != 0 || !in.read(reinterpret_cast<char*>(header), sizeof header))
        return false;
    if (header[0] != o.width || header[1] != o.height || header[2] != uint32_t(render::Aov::Count) || header[3] != spp) return false;
    const size_t floats = size_t(o.width) * o.height * 3;
    for (render::Image& img : aovs) {
        img.width = o.width;
        img.height = o.height;
        img.rgb.resize(floats);
        if (!in.read(reinterpret_cast<char*>(img.rgb.data()), std::streamsize(floats * sizeof(float)))) return false;
    }
    return in.peek() == std::char_traits<char>::eof();
}

// Written beside the final name and renamed onto it: a reader sees a whole file or none.
void writeFile(const std::string& path, const render::PathTracerOptions& o, uint32_t spp,
               const std::array<render::Image, size_t(render::Aov::Count)>& aovs) {
    const std::string temporary = path + ".tmp" + std::to_string(::getpid());
    {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        const uint32_t header[4] = {o.width, o.height, uint32_t(render::Aov::Count), spp};
        out.write(kMagic, sizeof kMagic);
        out.write(reinterpret_cast<const char*>(header), sizeof header);
        for (const render::Image& img : aovs) out.write(reinterpret_cast<const char*>(img.rgb.data()), std::streamsize(img.rgb.size() * sizeof(float)));
        if (!out) {
            std::remove(temporary.c_str());
            return;  // a full disk costs the next test a trace, nothing else
        }
    }
    if (std::rename(temporary.c_str(), path.c_str()) != 0) std::remove(temporary.c_str());
}

// Holds an exclusive lock on `path` for its lifetime (none if the file cannot be opened: then two processes
// may trace the same image, which costs time and nothing else).
class FileLock {
public:
    explicit FileLock(const std::string& path) : fd_(::open(path.c_str(), O_CREAT | O_RDWR | O_CLOEXEC, 0644)) {
        if (fd_ >= 0 && ::flock(fd_, LOCK_EX) != 0) {
            ::close(fd_);
            fd_ = -1;
        }
    }
    ~FileLock() {
        if (fd_ >= 0) ::close(fd_);  // closing releases the lock
    }
    FileLock(const FileLock&) = delete;
    FileLock& operator=(const FileLock&) = delete;

private:
    int fd_;
};

}  // namespace

namespace {

// The path tracer's creation and samples recorded on a null device with `capabilities` ("" if it refuses them).
std::string recordedTrace(const rhi::Capabilities* capabilities, const scenes::SceneGeometry& scene, const render::PathTracerOptions& options,
                          uint32_t spp) {
    std::unique_ptr<rhi::IDevice> null = rhi::createNullDevice(capabilities);
    std::ostringstream recording;
    {
        std::unique_ptr<rhi::IDevice> recorder = rhi::createRecordingDevice(*null, recording);
        std::string error;
        auto tracer = render::PathTracer::create(*recorder, scene, options, &error);
        if (!tracer) return "";  // the real device refuses it too: the caller reports why
        tracer->addSamples(spp);
    }
    return recording.str();
}

}  // namespace

std::string referenceKey(TestDevice& td, const scenes::SceneGeometry& scene, const render::PathTracerOptions& options, uint32_t spp) {
    const std::string text = recordedTrace(&td.device->capabilities(), scene, options, spp);
    if (text.empty()) return "";
    Hash128 h;
    h.add(std::string("bricklight path-traced reference 1"));
    h.add(td.backend);
    h.add(td.device->capabilities().deviceName);
    h.add(text);
    addShaders(h, text, true);
    return h.hex();
}

std::string portableReferenceKey(const scenes::SceneGeometry& scene, const render::PathTracerOptions& options, uint32_t spp) {
    const std::string text = recordedTrace(nullptr, scene, options, spp);
    if (text.empty()) return "";
    Hash128 h;
    h.add(std::string("bricklight portable path-traced reference 1"));
    h.add(text);
    addShaders(h, text, false);
    return h.hex();
}

Reference pathTraced(TestDevice& td, const scenes::SceneGeometry& scene, const render::PathTracerOptions& options, uint32_t spp) {
    Reference r;
    r.samples_ = spp;
    auto trace = [&] {
        std::string error;
        auto pt = render::PathTracer::create(*td.device, scene, options, &error);
        INFO(error);
        REQUIRE(pt);
        pt->addSamples(spp);
        for (size_t a = 0; a < r.aovs_.size(); ++a) r.aovs_[a] = pt->read(render::Aov(a));
    };
    const std::string key = cacheEnabled() ? referenceKey(td, scene, options, spp) : "";
    if (key.empty()) {
        trace();
        return r;
    }
    ::mkdir(BRICKLIGHT_TEST_REFERENCE_DIR, 0755);  // gone since configuring (a cleaned build tree): made again
    const std::string base = std::string(BRICKLIGHT_TEST_REFERENCE_DIR) + "/" + td.backend + "-" + key;
    FileLock lock(base + ".lock");
    if (readFile(base + ".ref", options, spp, r.aovs_)) {
        r.fromCache_ = true;
        return r;
    }
    if (readCommittedReference(portableReferenceKey(scene, options, spp), options.width, options.height, spp, r.aovs_)) {
        r.fromCommitted_ = true;
        return r;
    }
    trace();
    writeFile(base + ".ref", options, spp, r.aovs_);
    return r;
}

Reference pathTraced(TestDevice& td, const scenes::SceneGeometry& scene, uint32_t size, uint32_t spp, bool jitter, uint32_t seed,
                     uint32_t maxBounces) {
    render::PathTracerOptions o;
    o.width = o.height = size;
    o.pixelJitter = jitter;
    o.seed = seed;
    o.maxBounces = maxBounces;
    return pathTraced(td, scene, o, spp);
}

}  // namespace bricklight::testing
