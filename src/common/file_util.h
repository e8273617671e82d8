// File helpers. Output goes to a temporary name in the target's folder and is renamed into place
// only when complete, so a crash or error never leaves half a PNG, cache or mesh behind.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace sm {

// Reads a whole file; throws sm::FileError naming the file when it cannot.
std::vector<uint8_t> readFile(const std::string& path);
std::string readTextFile(const std::string& path);

// Calls write(tmpPath), then renames tmpPath to path. On any exception the temporary is removed and
// the exception propagates; an existing file at path is untouched until the rename.
void writeFileAtomically(const std::string& path,
                         const std::function<void(const std::string&)>& write);
void writeBytesAtomically(const std::string& path, std::span<const uint8_t> bytes);

std::string fileExtension(const std::string& path);  // lower case, with the dot: ".vtu"
std::string directoryOf(const std::string& path);    // "" for a bare file name
std::string joinPath(const std::string& dir, const std::string& file);
bool fileExists(const std::string& path);
uint64_t fileSize(const std::string& path);

}  // namespace sm
