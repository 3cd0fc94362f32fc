// Whole-file reads and atomic writes, portable: POSIX calls on Unix, the wide-character Win32 calls
// on Windows (paths are UTF-8 at the API and converted to UTF-16 there).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace tetprobe {

// Reads the whole file at path (UTF-8); throws Error(Status::io) naming the path and the system's reason.
std::vector<uint8_t> read_file(const char* path);

// Writes size bytes to a temporary file next to path, flushes it to disk and renames it over path,
// so path holds either its old contents or all the new bytes, never a part. Throws Error(Status::io).
void write_file_atomically(const char* path, const uint8_t* data, size_t size);

}  // namespace tetprobe
