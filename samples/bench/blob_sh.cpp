#include "blob_sh.h"

#include "core/sh_encoding.h"
#include "core/store_format.h"
#include "core/store_layout.h"

#include <cstring>

namespace bench {

namespace {

// Map entry i of a probe map of the blob (16 or 32 bits).
uint32_t map_entry(const uint8_t* map, uint64_t width, size_t i) {
    if (width == 2) {
        uint16_t v;
        std::memcpy(&v, map + 2 * i, 2);
        return v;
    }
    uint32_t v;
    std::memcpy(&v, map + 4 * i, 4);
    return v;
}

}  // namespace

bool read_blob_sh(const tp_store* store, BlobSh* out, bool any_encoding) {
    const void* data = nullptr;
    size_t size = 0;
    return tp_store_blob(store, &data, &size) == TP_OK && read_blob_sh(data, size, out, any_encoding);
}

bool read_blob_sh(const void* blob, size_t size, BlobSh* out, bool any_encoding) {
    if (size < tetprobe::kHeaderSize) return false;
    const uint8_t* bytes = static_cast<const uint8_t*>(blob);
    tetprobe::StoreHeader h;
    tetprobe::SectionEntry s[tetprobe::kSectionCount];
    std::memcpy(&h, bytes, sizeof h);
    std::memcpy(s, bytes + sizeof h, sizeof s);
    if (h.format_version != tetprobe::kStoreFormatVersion || h.sh_encoding >= tetprobe::kShEncodingCount ||
        (h.sh_encoding != tetprobe::kShHalf && !any_encoding))
        return false;
    for (const tetprobe::SectionEntry& e : s)
        if (e.offset > size || e.size > size - e.offset) return false;
    out->encoding = h.sh_encoding;
    out->record_bytes = tetprobe::sh_record_bytes(tetprobe::ShEncoding(h.sh_encoding), h.layout == tetprobe::kLayoutFast);
    out->records = bytes + s[tetprobe::kSectionSh].offset;
    const bool half = h.sh_encoding == tetprobe::kShHalf;
    out->stride = half ? out->record_bytes / 2 : 0;
    out->sh = half ? reinterpret_cast<const uint16_t*>(out->records) : nullptr;
    // input -> stored: the blob's remap, or (nothing merged) its probe_source inverted.
    const uint64_t width = tetprobe::store_map_bytes(h.input_probe_count);
    out->input_remap.resize(h.input_probe_count);
    if (s[tetprobe::kSectionInputRemap].size != 0) {
        for (size_t i = 0; i < h.input_probe_count; ++i)
            out->input_remap[i] = map_entry(bytes + s[tetprobe::kSectionInputRemap].offset, width, i);
    } else {
        for (size_t j = 0; j < h.probe_count; ++j)
            out->input_remap[map_entry(bytes + s[tetprobe::kSectionProbeSource].offset, width, j)] = uint32_t(j);
    }
    return true;
}

}  // namespace bench
