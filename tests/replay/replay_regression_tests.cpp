// Recordings kept as files: the fuzzer's seeds (tests/fuzz/seeds/replay_fuzzer) and every input that once
// crashed, hung or threw (regressions/), each replayed on the null device with and without the validation
// wrapper: nothing thrown, bounded time, and an error, when there is one, that names a line. A regression
// file <name>.jsonl may have <name>.expect beside it: the text its error must contain, or "ok".
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "../fuzz/replay_fuzz_shaders.h"
#include "replay_test_support.h"

using namespace bricklight::rhi;
using namespace bricklight::testing;
namespace fs = std::filesystem;

namespace {

std::string readFile(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

std::vector<fs::path> recordings(const char* dir) {
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(dir))
        if (e.is_regular_file() && e.path().extension() != ".expect") files.push_back(e.path());
    std::sort(files.begin(), files.end());
    return files;
}

void replayFiles(const char* dir, bool expectations) {
    bricklight::fuzz::registerReplayFuzzShaders();
    const std::vector<fs::path> files = recordings(dir);
    REQUIRE_FALSE(files.empty());
    for (const fs::path& file : files) {
        const std::string text = readFile(file);
        for (bool validate : {true, false}) {
            INFO(file.filename().string() << (validate ? " (validation wrapper)" : " (bare null device)"));
            const ReplayResult r = replayText(text, validate);
            INFO("error: " << r.error);
            CHECK_FALSE(r.threw);
            CHECK(r.seconds < kReplaySecondsBound);
            if (!r.ok) CHECK(r.error.rfind("recording line ", 0) == 0);
            fs::path expect = file;
            expect.replace_extension(".expect");
            if (!expectations || !fs::exists(expect)) continue;
            std::string want = readFile(expect);
            while (!want.empty() && (want.back() == '\n' || want.back() == '\r')) want.pop_back();
            if (want == "ok") CHECK(r.ok);
            else CHECK(r.error.find(want) != std::string::npos);
        }
    }
}

}  // namespace

TEST_CASE("the replay fuzzer's seeds replay without a crash", "[replay]") { replayFiles(BRICKLIGHT_REPLAY_SEED_DIR, false); }

TEST_CASE("inputs that once failed replay as expected", "[replay]") { replayFiles(BRICKLIGHT_REPLAY_REGRESSION_DIR, true); }
