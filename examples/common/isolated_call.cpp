#include "isolated_call.h"

#if defined(__linux__)

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <new>
#include <thread>

#if defined(__SANITIZE_ADDRESS__)
#define BRICKLIGHT_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define BRICKLIGHT_ASAN 1
#endif
#endif

namespace bricklight::scenes {

namespace {

// The child's exit codes for what it reports without a reply.
constexpr int kExitOutOfMemory = 101, kExitException = 102, kExitWriteFailed = 103, kExitParentGone = 104;

// A field of /proc/<pid>/statm in bytes (0: total address space, 1: resident); 0 if unreadable.
uint64_t statmBytes(pid_t pid, int field) {
    char path[64];
    std::snprintf(path, sizeof path, "/proc/%d/statm", int(pid));
    FILE* f = std::fopen(path, "r");
    if (!f) return 0;
    unsigned long long values[2] = {0, 0};
    const int n = std::fscanf(f, "%llu %llu", &values[0], &values[1]);
    std::fclose(f);
    return n == 2 ? values[field] * uint64_t(sysconf(_SC_PAGESIZE)) : 0;
}

bool writeAll(int fd, const void* data, size_t size) {
    const auto* p = static_cast<const uint8_t*>(data);
    while (size) {
        const ssize_t n = ::write(fd, p, size);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return false;
        p += n;
        size -= size_t(n);
    }
    return true;
}

[[noreturn]] void runChild(int fd, pid_t parent, const std::function<std::vector<uint8_t>()>& work, const IsolationLimits& limits) {
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent) _exit(kExitParentGone);
    // A crash must end the child with its signal: handlers inherited from sanitizers or libFuzzer would
    // report it as their own finding, or exit with a status that hides the signal.
    sigset_t fatal;
    sigemptyset(&fatal);
    for (int sig : {SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGABRT, SIGTRAP, SIGSYS, SIGPIPE}) {
        signal(sig, SIG_DFL);
        sigaddset(&fatal, sig);
    }
    sigprocmask(SIG_UNBLOCK, &fatal, nullptr);
    const rlimit noCore{0, 0};
    setrlimit(RLIMIT_CORE, &noCore);
#if !defined(BRICKLIGHT_ASAN)
    if (const uint64_t inherited = statmBytes(getpid(), 0)) {
        const rlimit space{rlim_t(inherited + limits.memoryBytes), rlim_t(inherited + limits.memoryBytes)};
        setrlimit(RLIMIT_AS, &space);
    }
#endif
    std::set_new_handler([] { _exit(kExitOutOfMemory); });
    std::vector<uint8_t> bytes;
    try {
        bytes = work();
    } catch (const std::bad_alloc&) {
        _exit(kExitOutOfMemory);
    } catch (...) {
        _exit(kExitException);
    }
    const uint64_t size = bytes.size();
    // _exit, not exit: the parent's atexit handlers and static destructors (devices, libraries) are not
    // the child's to run.
    _exit(writeAll(fd, &size, sizeof size) && writeAll(fd, bytes.data(), bytes.size()) ? 0 : kExitWriteFailed);
}

enum class Outcome { Reply, EndOfPipe, TimedOut, OutOfMemory, TooLong, ReadFailed };

}  // namespace

bool runIsolated(const std::function<std::vector<uint8_t>()>& work, const IsolationLimits& limits, std::vector<uint8_t>* reply,
                 std::string* error) {
    auto fail = [&](const std::string& why) {
        if (error) *error = why;
        reply->clear();
        return false;
    };
    int fds[2];
    if (pipe2(fds, O_CLOEXEC) != 0) return fail("cannot start " + limits.what + ": " + std::strerror(errno));
    const uint64_t baseline = statmBytes(getpid(), 1);
    const pid_t parent = getpid();
    const pid_t pid = fork();
    if (pid < 0) {
        close(fds[0]);
        close(fds[1]);
        return fail("cannot start " + limits.what + ": " + std::strerror(errno));
    }
    if (pid == 0) {
        close(fds[0]);
        runChild(fds[1], parent, work, limits);
    }
    close(fds[1]);
    const int fd = fds[0];
    const auto start = std::chrono::steady_clock::now();
    const auto deadline = start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(limits.timeoutSeconds));
    reply->clear();
    uint8_t header[8];
    size_t headerBytes = 0;
    uint64_t expected = 0;
    Outcome outcome = Outcome::ReadFailed;
    std::vector<uint8_t> chunk(1 << 16);
    while (true) {
        const auto now = std::chrono::steady_clock::now();
        if (now >= deadline) {
            outcome = Outcome::TimedOut;
            break;
        }
        // Short waits: the child's memory is looked at between them.
        const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - now).count();
        pollfd p{fd, POLLIN, 0};
        const int ready = poll(&p, 1, int(std::min<long long>(left + 1, 50)));
        if (baseline && statmBytes(pid, 1) > baseline + limits.memoryBytes) {
            outcome = Outcome::OutOfMemory;
            break;
        }
        if (ready < 0 && errno != EINTR) break;
        if (ready <= 0) continue;
        const ssize_t n = read(fd, chunk.data(), chunk.size());
        if (n < 0 && (errno == EINTR || errno == EAGAIN)) continue;
        if (n < 0) break;
        if (n == 0) {
            outcome = Outcome::EndOfPipe;
            break;
        }
        size_t used = 0;
        while (headerBytes < sizeof header && used < size_t(n)) header[headerBytes++] = chunk[used++];
        if (headerBytes < sizeof header) continue;
        std::memcpy(&expected, header, sizeof expected);
        if (expected > limits.maxReplyBytes || reply->size() + (size_t(n) - used) > expected) {
            outcome = Outcome::TooLong;
            break;
        }
        reply->insert(reply->end(), chunk.begin() + long(used), chunk.begin() + n);
        if (reply->size() == expected) {
            outcome = Outcome::Reply;
            break;
        }
    }
    close(fd);
    // The child has sent all it will: end it (it may be exiting already, or hanging on after a cut-short
    // reply) and collect its status. After the end of the pipe it gets until the deadline to exit by itself.
    int status = 0;
    pid_t waited = 0;
    if (outcome == Outcome::EndOfPipe)
        while ((waited = waitpid(pid, &status, WNOHANG)) == 0 && std::chrono::steady_clock::now() < deadline)
            std::this_thread::sleep_for(std::chrono::milliseconds(2));
    if (waited == 0) {
        kill(pid, SIGKILL);
        while ((waited = waitpid(pid, &status, 0)) < 0 && errno == EINTR) {
        }
    }
    char took[32];
    std::snprintf(took, sizeof took, "%.3g s", limits.timeoutSeconds);
    const std::string mib = std::to_string(limits.memoryBytes >> 20) + " MiB";
    switch (outcome) {
        case Outcome::Reply:
            return true;
        case Outcome::TimedOut:
            return fail(limits.what + " timed out after " + took + (limits.timeoutHint.empty() ? "" : " " + limits.timeoutHint));
        case Outcome::OutOfMemory:
            return fail(limits.what + " exceeded the memory limit of " + mib + (limits.memoryHint.empty() ? "" : " " + limits.memoryHint));
        case Outcome::TooLong:
            return fail(limits.what + " sent a reply of more than " + std::to_string(limits.maxReplyBytes) + " bytes");
        case Outcome::ReadFailed:
            return fail("reading from " + limits.what + " failed: " + std::strerror(errno));
        case Outcome::EndOfPipe:
            break;
    }
    if (waited == pid && WIFSIGNALED(status)) {
        const int sig = WTERMSIG(status);
        if (sig == SIGKILL && std::chrono::steady_clock::now() >= deadline)
            return fail(limits.what + " timed out after " + took + (limits.timeoutHint.empty() ? "" : " " + limits.timeoutHint));
        return fail(limits.what + " crashed (signal " + std::to_string(sig) + ", " + strsignal(sig) + ")");
    }
    if (waited == pid && WIFEXITED(status)) {
        switch (WEXITSTATUS(status)) {
            case kExitOutOfMemory:
                return fail(limits.what + " exceeded the memory limit of " + mib + (limits.memoryHint.empty() ? "" : " " + limits.memoryHint));
            case kExitException:
                return fail(limits.what + " failed with an exception");
            case 0:
                return fail(limits.what + " ended without a complete reply");
            default:
                return fail(limits.what + " exited with status " + std::to_string(WEXITSTATUS(status)));
        }
    }
    return fail(limits.what + " ended without a reply");
}

}  // namespace bricklight::scenes

#else  // no fork(): callers check kIsolationAvailable

namespace bricklight::scenes {

bool runIsolated(const std::function<std::vector<uint8_t>()>&, const IsolationLimits& limits, std::vector<uint8_t>* reply,
                 std::string* error) {
    reply->clear();
    if (error) *error = "cannot run " + limits.what + " in a child process on this platform";
    return false;
}

}  // namespace bricklight::scenes

#endif
