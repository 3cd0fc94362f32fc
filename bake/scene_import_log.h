// Assimp's own messages: while a session lives, Assimp's warnings and errors on this thread are
// collected (for the scene's notes) instead of printed. Assimp prints only through its process-wide
// logger; the session installs a silent one when there is none (no file, no console) and attaches
// its collector. Sessions take one process-wide lock: that logger is not made for several threads.
#pragma once

#include <mutex>
#include <string>
#include <vector>

namespace tetprobe {

class AssimpSession {
public:
    AssimpSession();
    ~AssimpSession();
    AssimpSession(const AssimpSession&) = delete;
    AssimpSession& operator=(const AssimpSession&) = delete;

    // Warnings and errors so far, in order, without trailing newlines; repeats are kept once.
    const std::vector<std::string>& messages() const { return messages_; }

private:
    std::unique_lock<std::mutex> lock_;
    std::vector<std::string> messages_;
};

}  // namespace tetprobe
