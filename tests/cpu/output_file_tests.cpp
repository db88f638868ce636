// Output files: a path is checked before any work, and a write replaces the target only when it
// succeeded and checked out; otherwise the old file stays and no temporary file is left behind.
#include <catch2/catch.hpp>

#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <sstream>

#include "output_file.h"

using namespace bricklight::render;

namespace {

std::string scratchFolder() {
    char pattern[] = "/tmp/bricklight-output-XXXXXX";
    const char* made = mkdtemp(pattern);
    REQUIRE(made);
    return made;
}

std::string contents(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

bool writeText(const std::string& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
    return bool(out);
}

size_t entries(const std::string& folder) {
    size_t n = 0;
    if (FILE* p = popen(("ls -A '" + folder + "' | wc -l").c_str(), "r")) {
        if (std::fscanf(p, "%zu", &n) != 1) n = 0;
        pclose(p);
    }
    return n;
}

}  // namespace

TEST_CASE("output paths are checked before the work", "[output][cpu]") {
    const std::string folder = scratchFolder();
    std::string error;
    CHECK(checkOutputPath(folder + "/image.png", &error));
    CHECK_FALSE(checkOutputPath(folder + "/missing/image.png", &error));
    CHECK(error.find("missing") != std::string::npos);
    CHECK_FALSE(checkOutputPath(folder, &error));  // a folder, not a file
    CHECK_FALSE(checkOutputPath(folder + "/", &error));
    CHECK_FALSE(checkOutputPath("/dev/null", &error));  // exists, not a regular file
    CHECK(error.find("not a regular file") != std::string::npos);
    rmdir(folder.c_str());
}

TEST_CASE("a write replaces the target only when it succeeded", "[output][cpu]") {
    const std::string folder = scratchFolder();
    const std::string target = folder + "/image.png";
    REQUIRE(writeText(target, "old"));
    std::string error, tempSeen;
    // Success: the temporary file ends in the target's extension, and replaces the target.
    CHECK(writeFileAtomically(
        target, [&](const std::string& temp, std::string*) { tempSeen = temp; return writeText(temp, "new"); }, nullptr, &error));
    CHECK(contents(target) == "new");
    CHECK(tempSeen.size() > 4);
    CHECK(tempSeen.substr(tempSeen.size() - 4) == ".png");
    CHECK(tempSeen.find(folder + "/.") == 0);
    // A writer that fails, one that writes nothing, and a check that fails: the old file stays, nothing else is left.
    CHECK_FALSE(writeFileAtomically(
        target, [&](const std::string& temp, std::string* why) { writeText(temp, "half"); *why = "disk full"; return false; }, nullptr, &error));
    CHECK(error.find("disk full") != std::string::npos);
    CHECK_FALSE(writeFileAtomically(target, [&](const std::string& temp, std::string*) { return writeText(temp, ""); }, nullptr, &error));
    CHECK(error.find("empty") != std::string::npos);
    CHECK_FALSE(writeFileAtomically(
        target, [&](const std::string& temp, std::string*) { return writeText(temp, "bad"); },
        [](const std::string&, std::string* why) { *why = "reads back wrong"; return false; }, &error));
    CHECK(error.find("reads back wrong") != std::string::npos);
    CHECK(contents(target) == "new");
    CHECK(entries(folder) == 1);
    std::remove(target.c_str());
    rmdir(folder.c_str());
}
