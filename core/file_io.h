// Whole-file reads and atomic writes, portable: POSIX calls on Unix, the wide-character Win32 calls
// on Windows (paths are UTF-8 at the API and converted to UTF-16 there).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace tetprobe {

// Reads the whole file at path (UTF-8). Only a regular file is read (not a directory, device, FIFO
// or socket: /dev/zero would never end), and only when it holds at most max_bytes. Throws
// Error(Status::io) naming the path and the reason.
std::vector<uint8_t> read_file(const char* path, uint64_t max_bytes);

// Writes size bytes to path so that path holds either its old contents or all the new bytes, never
// a part: the bytes go to a temporary file next to the file path names, are flushed to disk, and the
// temporary file is renamed over it. A symbolic link is written through (its target is replaced, the
// link stays), an existing file keeps its permissions (a new one gets the process's default), and a
// path naming something other than a regular file is refused. The temporary file is named
// "<file name>.tetprobe-tmp-<process id>-<16 hex digits>"; it is removed on every failure, and a
// save also removes those of its own file left by a save that was killed (their process is gone and
// nobody holds them), never one another save is still writing. Throws Error(Status::io).
void write_file_atomically(const char* path, const uint8_t* data, size_t size);

}  // namespace tetprobe
