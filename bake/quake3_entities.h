// The entity lump of a Quake 3 level: text of blocks { "key" "value" ... }, one per entity.
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace tetprobe {

struct Quake3Entity {
    std::vector<std::pair<std::string, std::string>> keys;  // in file order
    size_t offset = 0;                                      // byte of its '{' in the lump, for messages

    // The value of the first `key` (Q3 keys are case-insensitive), or nullptr.
    const std::string* find(const char* key) const;
};

// Parses the lump's text (it may end with NUL bytes). A malformed lump throws Error(Status::scene)
// with a message starting with `where` and naming the byte.
std::vector<Quake3Entity> parse_quake3_entities(const char* text, size_t size, const std::string& where);

// Parses "x y z" (three numbers) into out; false if the value is not that.
bool parse_quake3_vector(const std::string& value, double out[3]);

}  // namespace tetprobe
