// Tests of the kit itself, on the null device (no GPU): the case list, notes for what a backend cannot
// report, and the plain runner's exit codes.
#include <catch2/catch.hpp>

#include <cstring>
#include <set>
#include <sstream>

#include "bricklight/conformance.h"
#include "bricklight/rhi_validation.h"

using namespace bricklight;
using conformance::Backend;
using conformance::Case;
using conformance::CaseContext;
using conformance::CaseResult;

namespace {
const char* const kSkipped = "barrier count unsupported by this backend: check skipped";

std::unique_ptr<rhi::IDevice> nullDevice() { return rhi::createNullDevice(); }

// A case that asks for the barrier count twice, as the hazard cases do.
void countTwice(CaseContext& ctx) {
    std::optional<uint64_t> before = ctx.barriers();
    std::optional<uint64_t> after = ctx.barriers();
    ctx.check(before.has_value() == after.has_value(), "the count came and went");
    if (before && after) ctx.output("barriers", {uint8_t(*after - *before)});
}
}  // namespace

TEST_CASE("kit/case_list", "[conformance][kit]") {
    const std::vector<Case>& all = conformance::cases();
    // docs/rhi.md and README.md state this number: change them with it.
    CHECK(all.size() == 60);
    std::set<std::string> names;
    for (size_t i = 0; i < all.size(); ++i) {
        INFO("case " << all[i].name);
        CHECK(names.insert(all[i].name).second);
        CHECK(std::strlen(all[i].covers) > 0);
        CHECK(all[i].run != nullptr);
        if (i > 0) CHECK(std::strcmp(all[i - 1].name, all[i].name) < 0);
    }
}

TEST_CASE("kit/barrier_count_unsupported_is_a_note", "[conformance][kit]") {
    const Case probe{"count_twice", "CaseContext::barriers", countTwice};
    SECTION("no barrierCount function") {
        CaseResult r = conformance::runCase(probe, Backend{"no-hook", nullDevice, {}});
        CHECK(r.passed);
        CHECK(r.notes == std::vector<std::string>{kSkipped});
    }
    SECTION("barrierCount that cannot tell") {
        Backend b{"foreign", nullDevice, [](rhi::IDevice&) -> std::optional<uint64_t> { return std::nullopt; }};
        CaseResult r = conformance::runCase(probe, b);
        CHECK(r.passed);
        CHECK(r.notes == std::vector<std::string>{kSkipped});
    }
    SECTION("barrierCount that counts, asked about the device the backend created") {
        static const rhi::IDevice* created = nullptr;
        static const rhi::IDevice* asked = nullptr;
        static uint64_t count = 0;
        Backend b{"counting",
                  [] {
                      auto d = rhi::createNullDevice();
                      created = d.get();
                      return d;
                  },
                  [](rhi::IDevice& d) -> std::optional<uint64_t> {
                      asked = &d;
                      return count += 3;
                  }};
        CaseResult r = conformance::runCase(probe, b);
        CHECK(r.passed);
        CHECK(r.notes.empty());
        CHECK(asked == created);
        REQUIRE(r.outputs.size() == 1);
        CHECK(r.outputs[0].bytes == std::vector<uint8_t>{3});
    }
}

TEST_CASE("kit/runner_exit_codes", "[conformance][kit]") {
    std::ostringstream out;
    conformance::RunOptions options;
    options.out = &out;
    Backend broken{"broken", [] { return std::unique_ptr<rhi::IDevice>(); }, {}};

    options.filters = {"storage_buffer_fill"};
    CHECK(conformance::runAll({broken}, options) == 1);
    CHECK(out.str().find("failed  broken/storage_buffer_fill") != std::string::npos);
    CHECK(out.str().find("backend 'broken' could not create a device") != std::string::npos);
    CHECK(out.str().find("0 runs passed, 1 failed") != std::string::npos);

    out.str("");
    options.filters = {"no_such_case"};
    CHECK(conformance::runAll({broken}, options) == 1);
    CHECK(out.str().find("no case matches") != std::string::npos);

    CHECK(conformance::runAll({}, options) == 1);
}
