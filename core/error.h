// The one exception type inside the library; the C ABI boundary turns it into a tp_status.
#pragma once

#include "capi/tetprobe.h"

#include <stdexcept>
#include <string>

namespace tetprobe {

class Error : public std::runtime_error {
public:
    Error(tp_status status, const std::string& message) : std::runtime_error(message), status_(status) {}
    tp_status status() const { return status_; }

private:
    tp_status status_;
};

}  // namespace tetprobe
