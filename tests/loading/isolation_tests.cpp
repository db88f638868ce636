// runIsolated: whatever the work in the child does (crash, hang, eat memory, throw, lie about its reply's
// length), the caller gets a message saying so, within its limits, and goes on.
#include "test_support.h"

#include <signal.h>
#include <unistd.h>

#include <cstring>
#include <thread>

#include "isolated_call.h"

using namespace bricklight;
using namespace bricklight::testing;

namespace {

std::string runChild(const std::function<std::vector<uint8_t>()>& work, scenes::IsolationLimits limits, double* seconds,
                     std::vector<uint8_t>* reply = nullptr) {
    std::vector<uint8_t> bytes;
    std::string error;
    limits.what = "the test's work";
    bool ok = false;
    *seconds = secondsOf([&] { ok = scenes::runIsolated(work, limits, &bytes, &error); });
    if (reply) *reply = bytes;
    return ok ? "ok" : error;
}

}  // namespace

TEST_CASE("loading: work in a child process returns its bytes or a clear error", "[loading]") {
    if (!scenes::kIsolationAvailable) return;
    scenes::IsolationLimits limits;
    limits.timeoutSeconds = 1.0;
    limits.memoryBytes = 256ull << 20;
    limits.maxReplyBytes = 1 << 20;
    double seconds = 0;
    std::vector<uint8_t> reply;
    CHECK(runChild([] { return std::vector<uint8_t>{7, 8, 9}; }, limits, &seconds, &reply) == "ok");
    CHECK(reply == std::vector<uint8_t>{7, 8, 9});
    CHECK(runChild([] { return std::vector<uint8_t>(1 << 19, 1); }, limits, &seconds, &reply) == "ok");
    CHECK(reply.size() == size_t(1 << 19));

    CHECK(matches(runChild([]() -> std::vector<uint8_t> {
                      raise(SIGSEGV);
                      return {};
                  }, limits, &seconds),
                  "^the test's work crashed \\(signal 11, Segmentation fault\\)$"));
    CHECK(matches(runChild([]() -> std::vector<uint8_t> { abort(); }, limits, &seconds), "crashed \\(signal 6, "));
    CHECK(matches(runChild([]() -> std::vector<uint8_t> {
                      volatile uint64_t spins = 0;
                      while (true) spins = spins + 1;
                  }, limits, &seconds),
                  "^the test's work timed out after 1 s$"));
    CHECK(seconds < 3.0);
    limits.timeoutHint = "(raise it with --import-timeout)";
    CHECK(matches(runChild([]() -> std::vector<uint8_t> {
                      std::this_thread::sleep_for(std::chrono::seconds(30));
                      return {};
                  }, limits, &seconds),
                  "timed out after 1 s \\(raise it with --import-timeout\\)$"));
    CHECK(seconds < 3.0);
    // Memory: pages actually touched, 16 MiB at a time, up to 2 GiB; the limit is 256 MiB.
    limits.timeoutSeconds = 20.0;
    CHECK(matches(runChild([]() -> std::vector<uint8_t> {
                      std::vector<std::unique_ptr<char[]>> blocks;
                      for (int i = 0; i < 128; ++i) {
                          blocks.emplace_back(new char[16 << 20]);
                          std::memset(blocks.back().get(), i, 16 << 20);
                      }
                      return {};
                  }, limits, &seconds),
                  "^the test's work exceeded the memory limit of 256 MiB$"));
    CHECK(seconds < 10.0);
    CHECK(matches(runChild([]() -> std::vector<uint8_t> { throw std::runtime_error("no"); }, limits, &seconds),
                  "failed with an exception"));
    CHECK(matches(runChild([]() -> std::vector<uint8_t> { _exit(3); }, limits, &seconds), "exited with status 3"));
    CHECK(matches(runChild([] { return std::vector<uint8_t>((1 << 20) + 1, 1); }, limits, &seconds), "sent a reply of more than 1048576 bytes"));
}
