// Registers the kit's cases as Catch2 tests at run time, one per (backend, case) plus a cross-backend
// comparison per case, so that ctest (through catch_discover_tests) lists each one by name.
#include <catch2/catch.hpp>

#include "bricklight/conformance_catch2.h"

namespace bricklight::conformance {

namespace {
class Invoker final : public Catch::ITestInvoker {
public:
    explicit Invoker(std::function<void()> f) : f_(std::move(f)) {}
    void invoke() const override { f_(); }

private:
    std::function<void()> f_;
};

void reportFailures(const std::vector<std::string>& failures) {
    for (const auto& f : failures) FAIL_CHECK(f);
}

// Notes are not failures (a check the backend cannot support, skipped): shown, never failing.
void reportNotes(const std::vector<std::string>& notes) {
    for (const auto& n : notes) WARN(n);
}

void add(const std::string& name, const std::string& tags, std::function<void()> body) {
    Catch::getMutableRegistryHub().registerTest(
        Catch::makeTestCase(new Invoker(std::move(body)), "", Catch::NameAndTags{name, tags}, CATCH_INTERNAL_LINEINFO));
}
}  // namespace

void registerCatchTests(const std::vector<Backend>& backends) {
    for (const Case& c : cases()) {
        for (const Backend& b : backends)
            add(b.name + "/" + c.name, "[conformance][" + b.name + "]", [c, b] {
                INFO("case " << c.name << " covers: " << c.covers);
                CaseResult r = runCase(c, b);
                reportFailures(r.failures);
                reportNotes(r.notes);
                CHECK(r.passed);
            });
        if (backends.size() >= 2) {
            Backend first = backends[0], second = backends[1];
            add("cross/" + std::string(c.name), "[conformance][cross]", [c, first, second] {
                INFO("case " << c.name << ": " << first.name << " vs " << second.name);
                CaseResult a = runCase(c, first);
                CaseResult b = runCase(c, second);
                reportFailures(a.failures);
                reportFailures(b.failures);
                REQUIRE(a.passed);
                REQUIRE(b.passed);
                reportFailures(compareOutputs(a, b));
                CHECK(!a.outputs.empty());
            });
        }
    }
}

}  // namespace bricklight::conformance
