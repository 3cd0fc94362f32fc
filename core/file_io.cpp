#include "core/file_io.h"

#include "core/error.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>

#if defined(_WIN32)
#ifndef WIN32_LEAN_AND_MEAN
#define WIN32_LEAN_AND_MEAN
#endif
#include <windows.h>
#else
#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>
#endif

namespace tetprobe {

namespace {

// Chunks of at most 1 GiB (a Win32 read or write takes a DWORD count).
constexpr size_t kChunk = size_t(1) << 30;

// The temporary files of a save: "<name><kTempInfix><process id>-<16 hex digits>".
const char* const kTempInfix = ".tetprobe-tmp-";
constexpr size_t kTempHexDigits = 16;

std::string too_large(const char* path, uint64_t bytes, uint64_t max_bytes) {
    return std::string("cannot load '") + path + "': the file has " + std::to_string(bytes) +
           " bytes, above the load cap of " + std::to_string(max_bytes) + " bytes (max_file_bytes)";
}

// 16 hex digits that differ between the saves of a process (a clock and a counter, mixed).
std::string unique_hex() {
    static std::atomic<uint64_t> counter{0};
    uint64_t x = uint64_t(std::chrono::steady_clock::now().time_since_epoch().count()) ^
                 (counter.fetch_add(1) * 0x9E3779B97F4A7C15ull);
    x ^= x >> 31;
    x *= 0xBF58476D1CE4E5B9ull;
    x ^= x >> 29;
    char text[kTempHexDigits + 1];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(x));
    return text;
}

// The process id a temporary file name of `name` carries, or 0 when the entry is not one of them
// (exactly the prefix, decimal digits, '-', 16 lowercase hex digits).
unsigned long temp_owner(const std::string& entry, const std::string& prefix) {
    if (entry.size() <= prefix.size() || entry.compare(0, prefix.size(), prefix) != 0) return 0;
    size_t i = prefix.size(), digits = 0;
    unsigned long pid = 0;
    for (; i < entry.size() && entry[i] >= '0' && entry[i] <= '9' && digits < 10; ++i, ++digits)
        pid = pid * 10 + unsigned(entry[i] - '0');
    if (digits == 0 || i >= entry.size() || entry[i] != '-' || entry.size() - i - 1 != kTempHexDigits) return 0;
    for (++i; i < entry.size(); ++i)
        if (!((entry[i] >= '0' && entry[i] <= '9') || (entry[i] >= 'a' && entry[i] <= 'f'))) return 0;
    return pid;
}

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

struct HandleCloser {
    HANDLE handle;
    ~HandleCloser() {
        if (handle != INVALID_HANDLE_VALUE) CloseHandle(handle);
    }
};

// The file a path finally names, symbolic links followed; the path itself when it does not exist.
std::wstring final_path(const std::wstring& path) {
    HANDLE h = CreateFileW(path.c_str(), 0, FILE_SHARE_READ | FILE_SHARE_WRITE | FILE_SHARE_DELETE, nullptr,
                           OPEN_EXISTING, FILE_FLAG_BACKUP_SEMANTICS, nullptr);
    if (h == INVALID_HANDLE_VALUE) return path;
    HandleCloser closer{h};
    std::wstring resolved(MAX_PATH, L'\0');
    for (;;) {
        const DWORD n = GetFinalPathNameByHandleW(h, &resolved[0], DWORD(resolved.size()), FILE_NAME_NORMALIZED);
        if (n == 0) return path;
        if (n < resolved.size()) {
            resolved.resize(n);
            return resolved;
        }
        resolved.resize(size_t(n) + 1);
    }
}

bool process_alive(unsigned long pid) {
    HANDLE process = OpenProcess(SYNCHRONIZE, FALSE, DWORD(pid));
    if (!process) return GetLastError() == ERROR_ACCESS_DENIED;  // exists, not ours to open
    const bool running = WaitForSingleObject(process, 0) == WAIT_TIMEOUT;
    CloseHandle(process);
    return running;
}

// Removes the temporary files of `name` in `directory` left by saves whose process is gone; one a
// save still writes is open without sharing, so deleting it fails (best effort throughout).
void remove_stale_temporaries(const std::wstring& directory, const std::wstring& name) {
    const std::wstring prefix = name + wide_path(kTempInfix);
    WIN32_FIND_DATAW entry;
    HANDLE find = FindFirstFileW((directory + prefix + L"*").c_str(), &entry);
    if (find == INVALID_HANDLE_VALUE) return;
    do {
        const std::wstring found = entry.cFileName;
        if (found.size() <= prefix.size() || found.compare(0, prefix.size(), prefix) != 0) continue;
        std::string rest;  // after the prefix the pattern is ASCII
        for (wchar_t c : found.substr(prefix.size())) rest.push_back(c < 128 ? char(c) : '?');
        const unsigned long pid = temp_owner(rest, "");
        if (pid == 0 || pid == GetCurrentProcessId() || process_alive(pid)) continue;
        if (entry.dwFileAttributes & FILE_ATTRIBUTE_DIRECTORY) continue;
        DeleteFileW((directory + found).c_str());
    } while (FindNextFileW(find, &entry));
    FindClose(find);
}

#else

std::string system_error(const std::string& what, const std::string& path) {
    return what + " '" + path + "': " + std::strerror(errno);
}

struct FdCloser {
    int fd;
    ~FdCloser() {
        if (fd >= 0) ::close(fd);
    }
};

const char* kind_of(mode_t mode) {
    if (S_ISDIR(mode)) return "a directory";
    if (S_ISFIFO(mode)) return "a FIFO";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    if (S_ISSOCK(mode)) return "a socket";
    return "not a regular file";
}

std::string directory_of(const std::string& path) {
    const size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? "." : (slash == 0 ? "/" : path.substr(0, slash));
}

// The file a path finally names: symbolic links followed (relative ones from their own directory),
// the last one possibly dangling (then its target is created, as `echo > link` does).
std::string follow_links(const char* path) {
    std::string current = path;
    for (int hops = 0; hops < 40; ++hops) {
        struct stat st;
        if (::lstat(current.c_str(), &st) != 0 || !S_ISLNK(st.st_mode)) return current;
        std::vector<char> target(size_t(st.st_size > 0 ? st.st_size : 255) + 1);
        for (;;) {
            const ssize_t n = ::readlink(current.c_str(), target.data(), target.size());
            if (n < 0) throw Error(Status::io, system_error("cannot read the symbolic link", current));
            if (size_t(n) < target.size()) {
                target.resize(size_t(n));
                break;
            }
            target.resize(target.size() * 2);
        }
        const std::string link(target.begin(), target.end());
        current = !link.empty() && link[0] == '/' ? link : directory_of(current) + "/" + link;
    }
    throw Error(Status::io, std::string("cannot save to '") + path + "': too many levels of symbolic links");
}

// Whether another process may still be writing the temporary file open as fd: its owner's process
// is alive, or someone holds the file's lock (a save on another machine sharing the directory).
bool held_by_a_writer(int fd, unsigned long pid) {
    if (::kill(pid_t(pid), 0) == 0 || errno != ESRCH) return true;
    return ::flock(fd, LOCK_EX | LOCK_NB) != 0;
}

// Removes the temporary files of `name` in `directory` that a killed save left behind. Best effort:
// a file another save still writes is left alone, and so is one that is not what it was when looked at.
void remove_stale_temporaries(const std::string& directory, const std::string& name) {
    DIR* dir = ::opendir(directory.c_str());
    if (!dir) return;
    const std::string prefix = name + kTempInfix;
    const int dir_fd = ::dirfd(dir);
    while (const dirent* entry = ::readdir(dir)) {
        const unsigned long pid = temp_owner(entry->d_name, prefix);
        if (pid == 0 || pid == static_cast<unsigned long>(::getpid())) continue;  // not ours, or this process's own
        const int fd = ::openat(dir_fd, entry->d_name, O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
        if (fd < 0) continue;
        FdCloser closer{fd};
        struct stat opened, named;
        if (held_by_a_writer(fd, pid) || ::fstat(fd, &opened) != 0 || !S_ISREG(opened.st_mode)) continue;
        if (::fstatat(dir_fd, entry->d_name, &named, AT_SYMLINK_NOFOLLOW) != 0 || named.st_ino != opened.st_ino ||
            named.st_dev != opened.st_dev)
            continue;
        ::unlinkat(dir_fd, entry->d_name, 0);
    }
    ::closedir(dir);
}

void write_all(int fd, const uint8_t* data, size_t size, const std::string& path) {
    while (size > 0) {
        const ssize_t written = ::write(fd, data, std::min(size, kChunk));
        if (written < 0) {
            if (errno == EINTR) continue;
            throw Error(Status::io, system_error("cannot write", path));
        }
        data += written;
        size -= size_t(written);
    }
}

// Creates and locks a new temporary file for target; its name goes to *temp. The lock is taken
// before anything is written and kept until the file has its final name, and the name is checked to
// still be this file once locked (a cleaner may have removed it between creation and lock).
int create_temporary(const std::string& target, std::string* temp, mode_t mode) {
    for (int attempt = 0; attempt < 100; ++attempt) {
        *temp = target + kTempInfix + std::to_string(::getpid()) + "-" + unique_hex();
        const int fd = ::open(temp->c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, mode);
        if (fd < 0) {
            if (errno == EEXIST) continue;
            throw Error(Status::io, system_error("cannot create a temporary file for", target));
        }
        // A file system without locks leaves the process id alone to guard the file.
        const bool contended = ::flock(fd, LOCK_EX | LOCK_NB) != 0 && errno == EWOULDBLOCK;
        struct stat opened, named;
        if (!contended && ::fstat(fd, &opened) == 0 && ::lstat(temp->c_str(), &named) == 0 &&
            opened.st_ino == named.st_ino && opened.st_dev == named.st_dev)
            return fd;
        ::close(fd);  // a cleaner holds it (and removes it) or removed it already: try another name
    }
    throw Error(Status::io, "cannot create a temporary file for '" + target + "': every name tried was taken");
}

#endif

}  // namespace

#if defined(_WIN32)

std::vector<uint8_t> read_file(const char* path, uint64_t max_bytes) {
    const std::wstring wide = wide_path(path);
    const DWORD attributes = GetFileAttributesW(wide.c_str());
    if (attributes != INVALID_FILE_ATTRIBUTES && (attributes & FILE_ATTRIBUTE_DIRECTORY))
        throw Error(Status::io, std::string("cannot load '") + path + "': it is a directory, not a regular file");
    HANDLE file = CreateFileW(wide.c_str(), GENERIC_READ, FILE_SHARE_READ, nullptr, OPEN_EXISTING,
                              FILE_ATTRIBUTE_NORMAL, nullptr);
    if (file == INVALID_HANDLE_VALUE) throw Error(Status::io, windows_error("cannot open", path, GetLastError()));
    HandleCloser closer{file};
    if (GetFileType(file) != FILE_TYPE_DISK)
        throw Error(Status::io, std::string("cannot load '") + path + "': it is a device or a pipe, not a regular file");
    LARGE_INTEGER size;
    if (!GetFileSizeEx(file, &size)) throw Error(Status::io, windows_error("cannot read", path, GetLastError()));
    if (uint64_t(size.QuadPart) > max_bytes) throw Error(Status::io, too_large(path, uint64_t(size.QuadPart), max_bytes));
    std::vector<uint8_t> bytes(size_t(size.QuadPart));
    size_t done = 0;
    while (done < bytes.size()) {
        DWORD got = 0;
        if (!ReadFile(file, bytes.data() + done, DWORD(std::min(bytes.size() - done, kChunk)), &got, nullptr))
            throw Error(Status::io, windows_error("cannot read", path, GetLastError()));
        if (got == 0) break;  // shorter than it was a moment ago
        done += got;
    }
    bytes.resize(done);
    return bytes;
}

void write_file_atomically(const char* path, const uint8_t* data, size_t size) {
    const std::wstring target = final_path(wide_path(path));
    const size_t slash = target.find_last_of(L"\\/");
    const std::wstring directory = slash == std::wstring::npos ? L"" : target.substr(0, slash + 1);
    const std::wstring name = slash == std::wstring::npos ? target : target.substr(slash + 1);
    const DWORD existing = GetFileAttributesW(target.c_str());
    if (existing != INVALID_FILE_ATTRIBUTES && (existing & FILE_ATTRIBUTE_DIRECTORY))
        throw Error(Status::io, std::string("cannot save to '") + path + "': it is a directory");
    remove_stale_temporaries(directory, name);
    // No sharing while the bytes are written: a cleaner's delete fails (and so does any other opener).
    std::wstring temp;
    HANDLE file = INVALID_HANDLE_VALUE;
    for (int attempt = 0; attempt < 100 && file == INVALID_HANDLE_VALUE; ++attempt) {
        temp = target + wide_path(kTempInfix) + std::to_wstring(GetCurrentProcessId()) + L"-" +
               wide_path(unique_hex().c_str());
        file = CreateFileW(temp.c_str(), GENERIC_WRITE, 0, nullptr, CREATE_NEW, FILE_ATTRIBUTE_NORMAL, nullptr);
        if (file == INVALID_HANDLE_VALUE && GetLastError() != ERROR_FILE_EXISTS) break;
    }
    if (file == INVALID_HANDLE_VALUE)
        throw Error(Status::io, windows_error("cannot create a temporary file for", path, GetLastError()));
    DWORD code = 0;
    const char* step = nullptr;
    while (size > 0 && !step) {
        const DWORD chunk = DWORD(std::min(size, kChunk));
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
    // Over an existing file ReplaceFileW keeps its attributes and access control (its "mode").
    if (!step && existing != INVALID_FILE_ATTRIBUTES) {
        if (!ReplaceFileW(target.c_str(), temp.c_str(), nullptr, REPLACEFILE_IGNORE_MERGE_ERRORS, nullptr, nullptr))
            code = GetLastError(), step = "cannot replace";
    } else if (!step && !MoveFileExW(temp.c_str(), target.c_str(), MOVEFILE_REPLACE_EXISTING | MOVEFILE_WRITE_THROUGH)) {
        code = GetLastError(), step = "cannot rename the temporary file onto";
    }
    if (step) {
        DeleteFileW(temp.c_str());
        throw Error(Status::io, windows_error(step, path, code));
    }
}

#else

std::vector<uint8_t> read_file(const char* path, uint64_t max_bytes) {
    // Non-blocking: opening a FIFO must not wait for a writer (it is refused below anyway).
    const int fd = ::open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) throw Error(Status::io, system_error("cannot open", path));
    FdCloser closer{fd};
    struct stat st;
    if (::fstat(fd, &st) != 0) throw Error(Status::io, system_error("cannot read", path));
    if (!S_ISREG(st.st_mode))
        throw Error(Status::io, std::string("cannot load '") + path + "': it is " + kind_of(st.st_mode) +
                                    ", not a regular file");
    if (uint64_t(st.st_size) > max_bytes) throw Error(Status::io, too_large(path, uint64_t(st.st_size), max_bytes));
    // The size it had when opened, at most (bytes appended meanwhile are not read: the store then
    // fails validation as a truncated one).
    std::vector<uint8_t> bytes(size_t(st.st_size));
    size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::read(fd, bytes.data() + done, std::min(bytes.size() - done, kChunk));
        if (n < 0) {
            if (errno == EINTR) continue;
            throw Error(Status::io, system_error("cannot read", path));
        }
        if (n == 0) break;
        done += size_t(n);
    }
    bytes.resize(done);
    return bytes;
}

void write_file_atomically(const char* path, const uint8_t* data, size_t size) {
    const std::string target = follow_links(path);
    struct stat existing;
    const bool exists = ::stat(target.c_str(), &existing) == 0;
    // Renaming over a device or a FIFO would replace the node itself (/dev/null for a root process).
    if (exists && !S_ISREG(existing.st_mode))
        throw Error(Status::io, "cannot save to '" + target + "': it is " + kind_of(existing.st_mode) +
                                    ", not a regular file");
    const std::string directory = directory_of(target);
    remove_stale_temporaries(directory, target.substr(target.find_last_of('/') + 1));
    std::string temp;
    // A new file gets the permissions any file the process creates gets (the umask applies).
    const int fd = create_temporary(target, &temp, 0666);
    try {
        write_all(fd, data, size, target);
        if (exists) {  // keep the file's owner (best effort: only a privileged process may) and permissions
            if (existing.st_uid != ::geteuid() || existing.st_gid != ::getegid())
                (void)!::fchown(fd, existing.st_uid, existing.st_gid);
            if (::fchmod(fd, existing.st_mode & 07777) != 0)
                throw Error(Status::io, system_error("cannot set the permissions of", target));
        }
        if (::fsync(fd) != 0) throw Error(Status::io, system_error("cannot flush", target));
        // Renamed while still open and locked, so that no cleaner can take it before it has its name.
        if (::rename(temp.c_str(), target.c_str()) != 0)
            throw Error(Status::io, system_error("cannot rename the temporary file onto", target));
    } catch (...) {
        ::unlink(temp.c_str());
        ::close(fd);
        throw;
    }
    ::close(fd);  // flushed already: a late error here would not make the renamed file any less whole
    // Make the rename itself durable (best effort: some file systems refuse fsync on directories).
    const int dir_fd = ::open(directory.c_str(), O_RDONLY | O_CLOEXEC);
    if (dir_fd >= 0) {
        ::fsync(dir_fd);
        ::close(dir_fd);
    }
}

#endif

}  // namespace tetprobe
