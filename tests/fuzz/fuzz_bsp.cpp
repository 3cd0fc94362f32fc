// libFuzzer target: Quake 3 level reading (bake/quake3_bsp) must accept or refuse any bytes with
// Error(Status::scene), never read out of bounds, and an accepted level's indices name its vertices.
// The seed (seeds/fuzz_bsp/) is a small level of every face type, like the unit test's.
#include "bake/quake3_bsp.h"
#include "core/error.h"

#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    try {
        const tetprobe::Quake3Level level = tetprobe::parse_quake3_bsp(data, size, "fuzz.bsp");
        for (uint32_t i : level.indices)
            if (size_t(i) >= level.vertices.size() / 3) std::abort();
    } catch (const tetprobe::Error& e) {
        if (e.status() != tetprobe::Status::scene) std::abort();
    }
    return 0;
}
