#include "coherent_timing.h"

#include "bench_timing.h"

#include "core/half.h"
#include "core/sh_blend.h"

#include <cstring>

namespace bench {

namespace {

tp_location locate(const tp_store* store, const float* p, int32_t* hint) {
    tp_location loc;
    std::memset(&loc, 0, sizeof loc);
    loc.struct_size = sizeof loc;
    tp_store_locate(store, p, hint, &loc);
    return loc;
}

double ns_per_query(double seconds, size_t queries) { return 1e9 * seconds / double(queries); }

}  // namespace

std::vector<int32_t> first_hints(const tp_store* store, const ObjectPaths& paths) {
    std::vector<int32_t> hints(paths.objects, -1);
    for (size_t o = 0; o < paths.objects; ++o) locate(store, paths.at(o, 0), &hints[o]);
    return hints;
}

double time_coherent_single(const tp_store* store, const ObjectPaths& paths, float* sink) {
    const std::vector<int32_t> start = first_hints(store, paths);
    return ns_per_query(median_seconds([&] {
                            float out[27], acc = 0;
                            const Clock::time_point t0 = Clock::now();
                            for (size_t o = 0; o < paths.objects; ++o) {
                                int32_t hint = start[o];
                                for (size_t f = 1; f < paths.frames; ++f) {
                                    tp_store_interpolate(store, paths.at(o, f), &hint, out);
                                    acc += out[0];
                                }
                            }
                            const double s = seconds_since(t0);
                            *sink += acc;
                            return s;
                        }),
                        paths.timed_queries());
}

double time_blend_floor(const tp_store* store, const BlobSh& blob, const ObjectPaths& paths, float* sink) {
    const std::vector<int32_t> start = first_hints(store, paths);
    std::vector<const uint16_t*> sh;
    std::vector<float> weights;
    sh.reserve(4 * paths.timed_queries());
    weights.reserve(4 * paths.timed_queries());
    for (size_t o = 0; o < paths.objects; ++o) {
        int32_t hint = start[o];
        for (size_t f = 1; f < paths.frames; ++f) {
            const tp_location loc = locate(store, paths.at(o, f), &hint);
            for (int k = 0; k < 4; ++k) {
                sh.push_back(blob.sh + blob.stride * blob.input_remap[loc.probes[k]]);
                weights.push_back(loc.weights[k]);
            }
        }
    }
    const size_t n = paths.timed_queries();
    return ns_per_query(median_seconds([&] {
                            float out[27], acc = 0;
                            const Clock::time_point t0 = Clock::now();
                            for (size_t i = 0; i < n; ++i) {
                                tetprobe::blend_sh_halves(&sh[4 * i], &weights[4 * i], out);
                                acc += out[0];
                            }
                            const double s = seconds_since(t0);
                            *sink += acc;
                            return s;
                        }),
                        n);
}

double time_blend_floor_records(const tp_store* store, const BlobSh& blob, const ObjectPaths& paths, float* sink) {
    const std::vector<int32_t> start = first_hints(store, paths);
    std::vector<const uint8_t*> records;
    std::vector<float> weights;
    records.reserve(4 * paths.timed_queries());
    weights.reserve(4 * paths.timed_queries());
    for (size_t o = 0; o < paths.objects; ++o) {
        int32_t hint = start[o];
        for (size_t f = 1; f < paths.frames; ++f) {
            const tp_location loc = locate(store, paths.at(o, f), &hint);
            for (int k = 0; k < 4; ++k) {
                records.push_back(blob.records + blob.record_bytes * blob.input_remap[loc.probes[k]]);
                weights.push_back(loc.weights[k]);
            }
        }
    }
    const tetprobe::ShBlendFunction blend = tetprobe::sh_blend_function(tetprobe::ShEncoding(blob.encoding));
    const size_t n = paths.timed_queries();
    return ns_per_query(median_seconds([&] {
                            float out[27], acc = 0;
                            const Clock::time_point t0 = Clock::now();
                            for (size_t i = 0; i < n; ++i) {
                                blend(&records[4 * i], &weights[4 * i], out);
                                acc += out[0];
                            }
                            const double s = seconds_since(t0);
                            *sink += acc;
                            return s;
                        }),
                        n);
}

}  // namespace bench
