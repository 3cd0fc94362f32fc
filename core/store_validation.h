// The one-time check of an untrusted blob: everything a query will later trust.
#pragma once

#include <cstddef>
#include <cstdint>

namespace tetprobe {

// Validates a blob held in 16-byte-aligned memory (size bytes, all readable). Throws
// Error(TP_ERROR_INVALID_BLOB) naming the first problem found, or Error(TP_ERROR_VERSION) for a
// well-formed blob of another format version. Reads nothing outside [data, data + size).
void validate_store_blob(const uint8_t* data, size_t size);

}  // namespace tetprobe
