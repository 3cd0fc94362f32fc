/* Probe clouds with a known linear SH field, and stores built from them (full library). */
#include "harness.h"

/* A linear field: SH coefficient k at p is a_k + b_k . p. */
float linear_field(int k, const float p[3]) {
    return (float)(0.1 * (k % 7) + 0.5 + 0.2 * p[0] * ((k % 3) - 1) + 0.15 * p[1] * ((k % 5) - 2) / 2.0 -
                   0.1 * p[2] * ((k % 4) - 1.5));
}

/* CLOUD probes in the cube [-1, 1]^3 with its 8 corners first (so the hull is the cube). */
void make_cloud(float* positions, float* sh, int count) {
    int i, k;
    for (i = 0; i < count; ++i) {
        float* p = positions + 3 * i;
        if (i < 8) {
            p[0] = (i & 1) ? 1.0f : -1.0f;
            p[1] = (i & 2) ? 1.0f : -1.0f;
            p[2] = (i & 4) ? 1.0f : -1.0f;
        } else {
            p[0] = uniform(-1, 1);
            p[1] = uniform(-1, 1);
            p[2] = uniform(-1, 1);
        }
        if (sh)
            for (k = 0; k < 27; ++k) sh[27 * i + k] = linear_field(k, p);
    }
}

tp_store* build_cloud(float* positions, float* sh, uint32_t flags) {
    tp_build_options options;
    tp_store* store = NULL;
    tp_build_options_init(&options);
    options.flags = flags;
    make_cloud(positions, sh, CLOUD);
    EXPECT_OK(tp_store_build(positions, 0, sh, 0, CLOUD, &options, &store));
    CHECK(store != NULL);
    return store;
}

tp_store* build_with_flags(const float* positions, const float* sh, size_t count, uint32_t flags) {
    tp_build_options options;
    tp_store* store = NULL;
    tp_build_options_init(&options);
    options.flags = flags;
    EXPECT_OK(tp_store_build(positions, 0, sh, 0, count, &options, &store));
    return store;
}

tp_store_info info_of(const tp_store* store) {
    tp_store_info info;
    memset(&info, 0, sizeof info);
    info.struct_size = sizeof info;
    EXPECT_OK(tp_store_get_info(store, &info));
    return info;
}
