/* Blobs and files of built stores: round trips, corrupt and truncated blobs, old formats, the compact layout. */
#include "harness.h"

void test_store_blobs_and_files(void) {
    static float positions[3 * CLOUD], sh[27 * CLOUD];
    tp_store *store = build_cloud(positions, sh, 0), *copy = NULL;
    const void* blob;
    const void* blob2;
    size_t size = 0, size2 = 0, cut;
    unsigned char* bytes;
    int rejected = 1, intact = 1;
    char path[256];
    if (!store) return;
    EXPECT_OK(tp_store_blob(store, &blob, &size));
    CHECK(size > 112);
    EXPECT_STATUS(tp_store_blob(NULL, &blob, &size), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_blob(store, NULL, &size), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_blob(store, &blob, NULL), TP_ERROR_INVALID_ARGUMENT);

    /* Round trip through memory: identical bytes and identical answers. */
    EXPECT_OK(tp_store_load(blob, size, &copy));
    if (copy) {
        float a[27], b[27];
        const float p[3] = {0.3f, -0.2f, 0.6f};
        EXPECT_OK(tp_store_blob(copy, &blob2, &size2));
        CHECK(size2 == size && memcmp(blob, blob2, size) == 0);
        EXPECT_OK(tp_store_interpolate(store, p, NULL, a));
        EXPECT_OK(tp_store_interpolate(copy, p, NULL, b));
        CHECK(memcmp(a, b, sizeof a) == 0);
        tp_store_release(copy);
        copy = NULL;
    }

    /* Round trip through a file, written atomically. */
    sprintf(path, "harness_store_%d.tpb", (int)(size % 1000));
    EXPECT_OK(tp_store_save_file(store, path));
    EXPECT_OK(tp_store_load_file(path, &copy));
    if (copy) {
        EXPECT_OK(tp_store_blob(copy, &blob2, &size2));
        CHECK(size2 == size && memcmp(blob, blob2, size) == 0);
        tp_store_release(copy);
        copy = NULL;
    }
    remove(path);
    EXPECT_STATUS(tp_store_save_file(store, "/nonexistent-dir/sub/store.tpb"), TP_ERROR_IO);
    EXPECT_STATUS(tp_store_save_file(store, NULL), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_save_file(NULL, path), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_load_file("/nonexistent-dir/store.tpb", &copy), TP_ERROR_IO);
    EXPECT_STATUS(tp_store_load_file(NULL, &copy), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_load_file(path, NULL), TP_ERROR_INVALID_ARGUMENT);
    CHECK(copy == NULL);

    /* Bad blobs: empty, null, every truncated prefix, one extra byte, flipped bytes, an unknown version. */
    EXPECT_STATUS(tp_store_load(blob, 0, &copy), TP_ERROR_INVALID_BLOB);
    EXPECT_STATUS(tp_store_load(NULL, size, &copy), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_load(blob, size, NULL), TP_ERROR_INVALID_ARGUMENT);
    bytes = (unsigned char*)malloc(size + 1);
    if (!bytes) return;
    memcpy(bytes, blob, size);
    for (cut = 0; cut < size; cut += (cut < 256 ? 1 : 97)) {
        tp_status status = tp_store_load(bytes, cut, &copy);
        if (status != TP_ERROR_INVALID_BLOB || copy != NULL) rejected = 0;
    }
    CHECK(rejected);
    bytes[size] = 0;
    EXPECT_STATUS(tp_store_load(bytes, size + 1, &copy), TP_ERROR_INVALID_BLOB);
    for (cut = 0; cut < size; cut += 61) {
        tp_status status;
        bytes[cut] ^= 0x5A;
        status = tp_store_load(bytes, size, &copy);
        if (status == TP_OK) {
            intact = 0;
            tp_store_release(copy);
            copy = NULL;
        }
        bytes[cut] ^= 0x5A;
    }
    CHECK(intact);
    bytes[0] = 'X';
    EXPECT_STATUS(tp_store_load(bytes, size, &copy), TP_ERROR_INVALID_BLOB);
    bytes[0] = 'T';
    {
        const unsigned char version = bytes[8]; /* format_version, little-endian uint32 after the magic */
        bytes[8] = 99;
        repair_checksum(bytes, size);
        EXPECT_STATUS(tp_store_load(bytes, size, &copy), TP_ERROR_VERSION);
        bytes[8] = version;
    }
    repair_checksum(bytes, size);
    EXPECT_OK(tp_store_load(bytes, size, &copy));
    tp_store_release(copy);
    copy = NULL;
    /* A file that is not a store. */
    {
        FILE* f = fopen(path, "wb");
        if (f) {
            fputs("not a store\n", f);
            fclose(f);
            EXPECT_STATUS(tp_store_load_file(path, &copy), TP_ERROR_INVALID_BLOB);
            remove(path);
        }
    }
    free(bytes);
    tp_store_release(store);
}

void test_compact_layout(void) {
    static float positions[3 * CLOUD], sh[27 * CLOUD];
    static const uint32_t extra_flags[3] = {0u, TP_BUILD_INDEX32, TP_BUILD_NO_EXTRAPOLATION};
    int variant;
    make_cloud(positions, sh, CLOUD);
    for (variant = 0; variant < 3; ++variant) {
        const uint32_t extra = extra_flags[variant];
        tp_store* fast = build_with_flags(positions, sh, CLOUD, extra);
        tp_store* compact = build_with_flags(positions, sh, CLOUD, extra | TP_BUILD_COMPACT);
        tp_store* reloaded = NULL;
        tp_store_info fast_info, compact_info;
        const void *fast_blob, *compact_blob, *reloaded_blob;
        size_t fast_size = 0, compact_size = 0, reloaded_size = 0;
        int i, k, same_cells = 1, same_kinds = 1, same_status = 1, walked_same = 1;
        double worst = 0.0;
        int32_t fast_hint = -1, compact_hint = -1;
        if (!fast || !compact) {
            tp_store_release(fast);
            tp_store_release(compact);
            return;
        }
        fast_info = info_of(fast);
        compact_info = info_of(compact);
        CHECK(fast_info.format_version == 6 && compact_info.format_version == 6);
        CHECK(fast_info.layout == TP_LAYOUT_FAST && compact_info.layout == TP_LAYOUT_COMPACT);
        CHECK(fast_info.flags == extra);
        CHECK(compact_info.flags == (extra | TP_BUILD_COMPACT));
        CHECK(compact_info.index_bits == fast_info.index_bits);
        CHECK(compact_info.cells == fast_info.cells && compact_info.inner_cells == fast_info.inner_cells);
        EXPECT_OK(tp_store_blob(fast, &fast_blob, &fast_size));
        EXPECT_OK(tp_store_blob(compact, &compact_blob, &compact_size));
        CHECK(compact_size < fast_size);
        CHECK(compact_info.bytes == compact_size);

        /* The same cell and weights within 1e-6, cold and walking, inside and outside the hull. */
        for (i = 0; i < 2000; ++i) {
            float p[3];
            tp_location a, b;
            tp_status sa, sb;
            p[0] = uniform(-1.5, 1.5);
            p[1] = uniform(-1.5, 1.5);
            p[2] = uniform(-1.5, 1.5);
            memset(&a, 0, sizeof a);
            memset(&b, 0, sizeof b);
            a.struct_size = b.struct_size = sizeof a;
            sa = tp_store_locate(fast, p, NULL, &a);
            sb = tp_store_locate(compact, p, NULL, &b);
            if (sa != sb || (sa != TP_OK && sa != TP_ERROR_OUTSIDE)) same_status = 0;
            if (sa != TP_OK || sb != TP_OK) continue;
            if (a.cell != b.cell) same_cells = 0;
            if (a.cell_kind != b.cell_kind) same_kinds = 0;
            for (k = 0; k < 4; ++k) {
                double d1 = fabs(weight_of(a.probes, a.weights, a.probes[k]) -
                                 weight_of(b.probes, b.weights, a.probes[k]));
                double d2 = fabs(weight_of(a.probes, a.weights, b.probes[k]) -
                                 weight_of(b.probes, b.weights, b.probes[k]));
                if (d1 > worst) worst = d1;
                if (d2 > worst) worst = d2;
            }
            {
                tp_status wa = tp_store_locate(fast, p, &fast_hint, &a);
                tp_status wb = tp_store_locate(compact, p, &compact_hint, &b);
                if (wa != wb || (wa == TP_OK && (a.cell != b.cell || fast_hint != compact_hint))) walked_same = 0;
            }
        }
        CHECK(same_status);
        CHECK(same_cells);
        CHECK(same_kinds);
        CHECK(walked_same);
        CHECK_NEAR(worst, 0.0, 1e-6);

        /* The compact blob round-trips byte for byte and stays compact. */
        EXPECT_OK(tp_store_load(compact_blob, compact_size, &reloaded));
        if (reloaded) {
            const float p[3] = {0.2f, -0.3f, 0.4f};
            float x[27], y[27];
            EXPECT_OK(tp_store_blob(reloaded, &reloaded_blob, &reloaded_size));
            CHECK(reloaded_size == compact_size && memcmp(reloaded_blob, compact_blob, compact_size) == 0);
            CHECK((info_of(reloaded).flags & TP_BUILD_COMPACT) != 0);
            EXPECT_OK(tp_store_interpolate(compact, p, NULL, x));
            EXPECT_OK(tp_store_interpolate(reloaded, p, NULL, y));
            CHECK(memcmp(x, y, sizeof x) == 0);
            tp_store_release(reloaded);
        }
        tp_store_release(compact);
        tp_store_release(fast);
    }
}

/* A blob of another format version (only the uint32 at byte 8 changed, nothing repaired) is refused
   as a version, not as corruption, and the message says to rebuild. */
void test_old_format_refused(void) {
    static float positions[3 * CLOUD], sh[27 * CLOUD];
    static const uint32_t versions[6] = {5u, 4u, 3u, 2u, 7u, 0u};
    int layout, v;
    make_cloud(positions, sh, CLOUD);
    for (layout = 0; layout < 2; ++layout) {
        tp_store* store = build_with_flags(positions, sh, CLOUD, layout ? TP_BUILD_COMPACT : 0u);
        const void* blob;
        size_t size = 0;
        unsigned char* bytes;
        if (!store) return;
        EXPECT_OK(tp_store_blob(store, &blob, &size));
        bytes = (unsigned char*)malloc(size);
        if (!bytes) {
            tp_store_release(store);
            return;
        }
        memcpy(bytes, blob, size);
        CHECK(bytes[8] == 6 && bytes[9] == 0 && bytes[10] == 0 && bytes[11] == 0);
        for (v = 0; v < 6; ++v) {
            tp_store* old = NULL;
            bytes[8] = (unsigned char)versions[v];
            EXPECT_STATUS(tp_store_load(bytes, size, &old), TP_ERROR_VERSION);
            CHECK(strstr(tp_last_error(), "rebuild") != NULL);
            CHECK(mentions_number(tp_last_error(), versions[v]));
            CHECK(old == NULL);
            tp_store_release(old);
        }
        bytes[8] = 6;
        {
            tp_store* again = NULL;
            EXPECT_OK(tp_store_load(bytes, size, &again));
            tp_store_release(again);
        }
        free(bytes);
        tp_store_release(store);
    }
}
