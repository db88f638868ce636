// Output files that are never lost half-written: the path is checked before the (long) work that fills it,
// and the file is written next to the target under a temporary name, checked, and renamed over it, so a
// failed or killed write leaves the old file (or none), never a truncated one.
#pragma once

#include <functional>
#include <string>

namespace bricklight::render {

// The characters that end a path's folders: "/", and on Windows "/\\" as well.
const char* pathSeparators();

// The target's folder exists and can be written, and the target is not a folder or a special file.
bool checkOutputPath(const std::string& path, std::string* error);

// Replaces `to` with `from` in one step (rename(), or MoveFileEx on Windows, where rename() refuses to replace an
// existing file); false with `why` on failure.
bool replaceFile(const std::string& from, const std::string& to, std::string* why);

// Calls write(tempPath) for a temporary file in the target's folder that ends in the target's extension (so
// writers that choose a format by extension still do), then check(tempPath) if given, then renames it over
// `path`. Any failure removes the temporary file and returns false with `error` naming the target.
bool writeFileAtomically(const std::string& path, const std::function<bool(const std::string& tempPath, std::string* error)>& write,
                         const std::function<bool(const std::string& tempPath, std::string* error)>& check, std::string* error);

}  // namespace bricklight::render
