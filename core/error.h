// The run time's own status codes and the one exception type inside the library; the C ABI
// boundary (capi/) turns both into a tp_status, whose values these are (checked there).
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

namespace tetprobe {

enum class Status : int32_t {
    ok = 0,
    invalid_argument = 1,
    out_of_memory = 2,
    io = 3,
    invalid_blob = 4,
    version = 5,
    degenerate = 6,
    tetgen = 7,
    cancelled = 8,
    outside = 9,
    scene = 10,
    unsupported = 11,
    buffer_too_small = 12,
    internal = 13,
};

class Error : public std::runtime_error {
public:
    Error(Status status, const std::string& message) : std::runtime_error(message), status_(status) {}
    Status status() const { return status_; }

private:
    Status status_;
};

}  // namespace tetprobe
