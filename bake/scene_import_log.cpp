#include "bake/scene_import_log.h"

#include <assimp/DefaultLogger.hpp>
#include <assimp/LogStream.hpp>

#include <algorithm>

namespace tetprobe {

namespace {

std::mutex assimp_lock;
std::vector<std::string>* collecting = nullptr;  // the live session's messages (guarded by assimp_lock)
const Assimp::Logger* attached_to = nullptr;     // the logger our stream is attached to

class Collector : public Assimp::LogStream {
public:
    void write(const char* message) override {
        if (!collecting || !message) return;
        std::string text(message);
        while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
        // The logger prefixes "Warn,  T0: " or "Error, T0: " (severity and thread): the note says it is Assimp's.
        const size_t thread = text.find(" T");
        const size_t colon = text.find(": ");
        if (thread != std::string::npos && colon != std::string::npos && thread < colon && colon < 16) text.erase(0, colon + 2);
        if (!text.empty() && std::find(collecting->begin(), collecting->end(), text) == collecting->end())
            collecting->push_back(text);
    }
};

}  // namespace

AssimpSession::AssimpSession() : lock_(assimp_lock) {
    // No logger yet: a silent one (no log file, no console stream). A logger the host application set
    // keeps its own streams; ours is added to it. The logger owns the streams attached to it.
    if (Assimp::DefaultLogger::isNullLogger()) Assimp::DefaultLogger::create(nullptr, Assimp::Logger::NORMAL, 0);
    Assimp::Logger* logger = Assimp::DefaultLogger::get();
    if (logger != attached_to) {
        logger->attachStream(new Collector, Assimp::Logger::Warn | Assimp::Logger::Err);
        attached_to = logger;
    }
    collecting = &messages_;
}

AssimpSession::~AssimpSession() { collecting = nullptr; }

}  // namespace tetprobe
