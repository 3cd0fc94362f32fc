#include "blob_sh.h"

#include "core/store_format.h"

#include <cstring>

namespace bench {

bool read_blob_sh(const tp_store* store, BlobSh* out) {
    const void* data = nullptr;
    size_t size = 0;
    if (tp_store_blob(store, &data, &size) != TP_OK || size < tetprobe::kHeaderSize) return false;
    const uint8_t* bytes = static_cast<const uint8_t*>(data);
    tetprobe::StoreHeader h;
    tetprobe::SectionEntry s[tetprobe::kSectionCount];
    std::memcpy(&h, bytes, sizeof h);
    std::memcpy(s, bytes + sizeof h, sizeof s);
    out->stride = (h.flags & tetprobe::kFlagCompact) ? tetprobe::kShHalvesCompact : tetprobe::kShHalvesFast;
    if (s[tetprobe::kSectionSh].size != 2ull * out->stride * h.probe_count ||
        s[tetprobe::kSectionInputRemap].size != 4ull * h.input_probe_count)
        return false;
    out->sh = reinterpret_cast<const uint16_t*>(bytes + s[tetprobe::kSectionSh].offset);
    out->input_remap.resize(h.input_probe_count);
    std::memcpy(out->input_remap.data(), bytes + s[tetprobe::kSectionInputRemap].offset, 4ull * h.input_probe_count);
    return true;
}

}  // namespace bench
