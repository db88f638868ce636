// Helpers of the loading tests: a fresh folder per test, timing, and message matching.
#pragma once

#include <catch2/catch.hpp>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <regex>
#include <string>

namespace bricklight::testing {

// This process's folder under the system's temporary folder; removed when the tests exit.
inline const std::filesystem::path& processFolder() {
    struct Folder {
        std::filesystem::path path = std::filesystem::temp_directory_path() / ("bricklight-loading-" + std::to_string(::getpid()));
        ~Folder() {
            std::error_code ignored;
            std::filesystem::remove_all(path, ignored);
        }
    };
    static const Folder folder;
    return folder.path;
}

// A fresh folder under this process's folder, named after the test.
inline std::string freshFolder(const std::string& name) {
    const std::filesystem::path dir = processFolder() / name;
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir.string();
}

inline bool matches(const std::string& text, const std::string& pattern) { return std::regex_search(text, std::regex(pattern)); }

// Seconds `f` takes.
template <typename F>
double secondsOf(F&& f) {
    const auto start = std::chrono::steady_clock::now();
    f();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Every refusal of a hostile file must come within this (the hangs found ran past 120 s).
constexpr double kMaxSeconds = 10.0;

}  // namespace bricklight::testing
