#include "bake/quake3_entities.h"

#include "core/error.h"

#include <cmath>
#include <cctype>
#include <cstdlib>
#include <strings.h>

namespace tetprobe {

namespace {

class Reader {
public:
    Reader(const char* text, size_t size, const std::string& where) : text_(text), size_(size), where_(where) {}

    // Skips white space and NULs; false at the end.
    bool skip() {
        while (at_ < size_ && (text_[at_] == '\0' || std::isspace(static_cast<unsigned char>(text_[at_])))) ++at_;
        return at_ < size_;
    }
    char peek() const { return text_[at_]; }
    size_t at() const { return at_; }
    void expect(char c) {
        if (!skip() || text_[at_] != c) fail(std::string("expected '") + c + "'");
        ++at_;
    }
    std::string quoted() {
        expect('"');
        const size_t start = at_;
        while (at_ < size_ && text_[at_] != '"') {
            if (text_[at_] == '\0') fail("a NUL byte inside a quoted string");
            ++at_;
        }
        if (at_ >= size_) fail("a quoted string that does not end");
        return std::string(text_ + start, text_ + at_++);
    }
    [[noreturn]] void fail(const std::string& what) const {
        throw Error(Status::scene, where_ + ": entities lump, byte " + std::to_string(at_) + ": " + what);
    }

private:
    const char* text_;
    size_t size_;
    size_t at_ = 0;
    const std::string& where_;
};

}  // namespace

const std::string* Quake3Entity::find(const char* key) const {
    for (const auto& kv : keys)
        if (strcasecmp(kv.first.c_str(), key) == 0) return &kv.second;
    return nullptr;
}

std::vector<Quake3Entity> parse_quake3_entities(const char* text, size_t size, const std::string& where) {
    std::vector<Quake3Entity> entities;
    Reader in(text, size, where);
    while (in.skip()) {
        Quake3Entity entity;
        entity.offset = in.at();
        in.expect('{');
        for (;;) {
            if (!in.skip()) in.fail("an entity that does not end (missing '}')");
            if (in.peek() == '}') break;
            std::string key = in.quoted();
            std::string value = in.quoted();
            entity.keys.emplace_back(std::move(key), std::move(value));
        }
        in.expect('}');
        entities.push_back(std::move(entity));
    }
    return entities;
}

bool parse_quake3_vector(const std::string& value, double out[3]) {
    const char* p = value.c_str();
    for (int a = 0; a < 3; ++a) {
        char* end = nullptr;
        out[a] = std::strtod(p, &end);
        if (end == p || !std::isfinite(out[a])) return false;
        p = end;
    }
    while (*p == ' ' || *p == '\t') ++p;
    return *p == '\0';
}

}  // namespace tetprobe
