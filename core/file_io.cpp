#include "core/file_io.h"

#include "core/error.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>

#if defined(_WIN32)
#ifndef WIN32_LEAN_AND_MEAN
#define WIN32_LEAN_AND_MEAN
#endif
#include <windows.h>
#else
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#endif

namespace tetprobe {

namespace {

#if defined(_WIN32)

std::string windows_error(const std::string& what, const char* path, DWORD code) {
    char text[256] = {0};
    const DWORD n = FormatMessageA(FORMAT_MESSAGE_FROM_SYSTEM | FORMAT_MESSAGE_IGNORE_INSERTS, nullptr, code, 0, text,
                                   sizeof text, nullptr);
    std::string reason = n ? std::string(text, n) : "error " + std::to_string(code);
    while (!reason.empty() && (reason.back() == '\n' || reason.back() == '\r' || reason.back() == ' ')) reason.pop_back();
    return what + " '" + path + "': " + reason;
}

// UTF-8 to UTF-16; invalid UTF-8 is an I/O error naming the path (no file can have that name).
std::wstring wide_path(const char* path) {
    const int n = MultiByteToWideChar(CP_UTF8, MB_ERR_INVALID_CHARS, path, -1, nullptr, 0);
    if (n <= 0) throw Error(Status::io, std::string("path '") + path + "' is not valid UTF-8");
    std::wstring wide(size_t(n), L'\0');
    MultiByteToWideChar(CP_UTF8, MB_ERR_INVALID_CHARS, path, -1, &wide[0], n);
    wide.resize(size_t(n - 1));
    return wide;
}

FILE* open_for_reading(const char* path) { return _wfopen(wide_path(path).c_str(), L"rb"); }

#else

std::string system_error(const std::string& what, const char* path) {
    return what + " '" + path + "': " + std::strerror(errno);
}

FILE* open_for_reading(const char* path) { return std::fopen(path, "rb"); }

#endif

}  // namespace

std::vector<uint8_t> read_file(const char* path) {
    FILE* file = open_for_reading(path);
    if (!file) throw Error(Status::io, std::string("cannot open '") + path + "': " + std::strerror(errno));
    std::vector<uint8_t> bytes;
    uint8_t buffer[1 << 16];
    try {
        for (;;) {
            const size_t n = std::fread(buffer, 1, sizeof buffer, file);
            bytes.insert(bytes.end(), buffer, buffer + n);
            if (n < sizeof buffer) break;
        }
    } catch (...) {
        std::fclose(file);
        throw;
    }
    const bool failed = std::ferror(file) != 0;
    std::fclose(file);
    if (failed) throw Error(Status::io, std::string("cannot read '") + path + "'");
    return bytes;
}

#if defined(_WIN32)

void write_file_atomically(const char* path, const uint8_t* data, size_t size) {
    const std::wstring target = wide_path(path);
    // CREATE_NEW never reuses a name another writer holds; the counter makes names unique in a process.
    static volatile LONG counter = 0;
    std::wstring temp;
    HANDLE file = INVALID_HANDLE_VALUE;
    for (int attempt = 0; attempt < 100 && file == INVALID_HANDLE_VALUE; ++attempt) {
        temp = target + L".tmp." + std::to_wstring(GetCurrentProcessId()) + L"." +
               std::to_wstring(InterlockedIncrement(&counter));
        file = CreateFileW(temp.c_str(), GENERIC_WRITE, 0, nullptr, CREATE_NEW, FILE_ATTRIBUTE_NORMAL, nullptr);
        if (file == INVALID_HANDLE_VALUE && GetLastError() != ERROR_FILE_EXISTS) break;
    }
    if (file == INVALID_HANDLE_VALUE)
        throw Error(Status::io, windows_error("cannot create a temporary file for", path, GetLastError()));
    DWORD code = 0;
    const char* step = nullptr;
    while (size > 0 && !step) {
        const DWORD chunk = size > (1u << 30) ? DWORD(1u << 30) : DWORD(size);
        DWORD written = 0;
        if (!WriteFile(file, data, chunk, &written, nullptr) || written == 0) {
            code = GetLastError();
            step = "cannot write";
        }
        data += written;
        size -= written;
    }
    if (!step && !FlushFileBuffers(file)) code = GetLastError(), step = "cannot flush";
    if (!CloseHandle(file) && !step) code = GetLastError(), step = "cannot close";
    if (!step && !MoveFileExW(temp.c_str(), target.c_str(), MOVEFILE_REPLACE_EXISTING | MOVEFILE_WRITE_THROUGH))
        code = GetLastError(), step = "cannot rename the temporary file onto";
    if (step) {
        DeleteFileW(temp.c_str());
        throw Error(Status::io, windows_error(step, path, code));
    }
}

#else

namespace {

void write_all(int fd, const uint8_t* data, size_t size, const char* path) {
    while (size > 0) {
        const ssize_t written = ::write(fd, data, size);
        if (written < 0) {
            if (errno == EINTR) continue;
            throw Error(Status::io, system_error("cannot write", path));
        }
        data += written;
        size -= size_t(written);
    }
}

}  // namespace

void write_file_atomically(const char* path, const uint8_t* data, size_t size) {
    std::string temp = std::string(path) + ".tmp.XXXXXX";
    std::vector<char> name(temp.begin(), temp.end());
    name.push_back('\0');
    const int fd = ::mkstemp(name.data());
    if (fd < 0) throw Error(Status::io, system_error("cannot create a temporary file for", path));
    bool open = true;
    try {
        write_all(fd, data, size, path);
        if (::fchmod(fd, 0644) != 0) throw Error(Status::io, system_error("cannot set permissions of", path));
        if (::fsync(fd) != 0) throw Error(Status::io, system_error("cannot flush", path));
        open = false;
        if (::close(fd) != 0) throw Error(Status::io, system_error("cannot close", path));
    } catch (...) {
        if (open) ::close(fd);
        ::unlink(name.data());
        throw;
    }
    if (std::rename(name.data(), path) != 0) {
        const std::string message = system_error("cannot rename the temporary file onto", path);
        ::unlink(name.data());
        throw Error(Status::io, message);
    }
    // Make the rename itself durable (best effort: some file systems refuse fsync on directories).
    std::string directory(path);
    const size_t slash = directory.find_last_of('/');
    directory = slash == std::string::npos ? "." : (slash == 0 ? "/" : directory.substr(0, slash));
    const int dir_fd = ::open(directory.c_str(), O_RDONLY);
    if (dir_fd >= 0) {
        ::fsync(dir_fd);
        ::close(dir_fd);
    }
}

#endif

}  // namespace tetprobe
