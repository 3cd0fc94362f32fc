/*
 * The committed golden blobs of tests/unit/golden (no build needed, so this runs with the run-time
 * library on every platform): their answers are known exactly, files round-trip, bad blobs and file
 * errors fail with the documented status.
 *
 * tiny_store_v6.bin: one tetrahedron with corners origin + {0, e_x, e_y, e_z}, origin (10, -20, 30.5),
 * built without extrapolation from five input probes (input 3 merged into input 1); store probe j
 * (inputs 0, 1, 2, 4) holds SH coefficient k = ((27 j + k) mod 23) / 4 - 2, exact in half precision.
 * tiny_store_<encoding>_<layout>[_quantized]_v6.bin: the same store in each SH encoding, layout and
 * position encoding, its SH a non-negative radiance (golden_radiance_sh); test_store_blob.cpp writes them.
 */
#include "harness.h"

static const double kOrigin[3] = {10.0, -20.0, 30.5};
static const uint32_t kInputOfProbe[4] = {0, 1, 2, 4};
static const uint32_t kProbeOfInput[5] = {0, 1, 2, 1, 3};

static float golden_sh(uint32_t probe, int k) { return (float)(((27 * (int)probe + k) % 23) * 0.25 - 2.0); }

/* Channel c of probe j: L0 = 1 + j / 2 + c / 4, coefficient i = L0 * ((9j + 3c + i) mod 7 - 3) / 8. */
static float golden_radiance_sh(uint32_t probe, int k) {
    const int c = k / 9, i = k % 9;
    const float l0 = 1.0f + 0.5f * (float)probe + 0.25f * (float)c;
    return i == 0 ? l0 : l0 * (float)((int)((9 * probe + 3 * (uint32_t)c + (uint32_t)i) % 7) - 3) * 0.125f;
}

/* World position of the point with local (tetrahedron) coordinates x, y, z. */
static void world(float out[3], double x, double y, double z) {
    out[0] = (float)(kOrigin[0] + x);
    out[1] = (float)(kOrigin[1] + y);
    out[2] = (float)(kOrigin[2] + z);
}

static unsigned char* read_golden(const char* name, size_t* size) {
    char path[1024];
    unsigned char* bytes;
    sprintf(path, "%.900s/tests/unit/golden/%s", g_repo_root, name);
    bytes = read_whole_file(path, size);
    if (!bytes) printf("FAIL cannot read %s\n", path);
    CHECK(bytes != NULL);
    return bytes;
}

static tp_store* load_golden(const char* name) {
    size_t size = 0;
    unsigned char* bytes = read_golden(name, &size);
    tp_store* store = NULL;
    if (!bytes) return NULL;
    EXPECT_OK(tp_store_load(bytes, size, &store));
    free(bytes); /* the store keeps its own copy */
    return store;
}

void test_golden_store_answers(void) {
    tp_store* store = load_golden("tiny_store_v6.bin");
    tp_store_info info;
    float out[27], weights[4], p[3];
    uint32_t probes[4];
    int i, k, exact = 1;
    if (!store) return;
    memset(&info, 0, sizeof info);
    info.struct_size = sizeof info;
    EXPECT_OK(tp_store_get_info(store, &info));
    CHECK(info.format_version == 6 && info.dimension == 3);
    CHECK(info.probes == 4 && info.input_probes == 5 && info.merged_probes == 1);
    CHECK(info.cells == 1 && info.inner_cells == 1 && info.outer_cells == 0);
    CHECK(info.index_bits == 16 && info.flags == TP_BUILD_NO_EXTRAPOLATION);
    CHECK(info.grid[0] == 1 && info.grid[1] == 1 && info.grid[2] == 1);
    CHECK(info.sh_encoding == TP_SH_ENCODING_HALF && info.layout == TP_LAYOUT_FAST && info.quantized_positions == 0);
    CHECK(info.hull_probes == 0);
    for (k = 0; k < 3; ++k) {
        CHECK(info.origin[k] == kOrigin[k]);
        CHECK(info.bounds_min[k] == (float)kOrigin[k] && info.bounds_max[k] == (float)(kOrigin[k] + 1.0));
    }
    /* Every input probe reads its survivor's SH, exactly (the values are exact halves). */
    for (i = 0; i < 5; ++i) {
        EXPECT_OK(tp_store_probe_sh(store, (uint32_t)i, out));
        for (k = 0; k < 27; ++k) exact &= out[k] == golden_sh(kProbeOfInput[i], k);
    }
    CHECK(exact);
    /* At each corner: weight 1 on that probe, its SH exactly. */
    for (i = 0; i < 4; ++i) {
        int32_t hint = -1;
        world(p, i == 1, i == 2, i == 3);
        EXPECT_OK(tp_store_weights(store, p, &hint, probes, weights));
        CHECK(hint == 0);
        CHECK(weight_of(probes, weights, kInputOfProbe[i]) == 1.0);
        EXPECT_OK(tp_store_interpolate(store, p, NULL, out));
        exact = 1;
        for (k = 0; k < 27; ++k) exact &= out[k] == golden_sh((uint32_t)i, k);
        CHECK(exact);
    }
    /* Inside: the weights are the barycentric coordinates (1 - x - y - z, x, y, z), the SH their blend. */
    {
        double worst_weight = 0.0, worst_sh = 0.0;
        for (i = 0; i < 200; ++i) {
            double x = uniform01(), y = uniform01(), z = uniform01(), expected[4];
            tp_location location;
            int slot;
            if (x + y + z >= 1.0) {
                x *= 0.3, y *= 0.3, z *= 0.3;
            }
            world(p, x, y, z);
            expected[0] = 1.0 - x - y - z, expected[1] = x, expected[2] = y, expected[3] = z;
            EXPECT_OK(tp_store_weights(store, p, NULL, probes, weights));
            EXPECT_OK(tp_store_interpolate(store, p, NULL, out));
            for (slot = 0; slot < 4; ++slot) {
                double d = fabs(weight_of(probes, weights, kInputOfProbe[slot]) - expected[slot]);
                if (d > worst_weight) worst_weight = d;
            }
            for (k = 0; k < 27; ++k) {
                double blend = 0.0, d;
                for (slot = 0; slot < 4; ++slot) blend += expected[slot] * golden_sh((uint32_t)slot, k);
                d = fabs(out[k] - blend);
                if (d > worst_sh) worst_sh = d;
            }
            memset(&location, 0, sizeof location);
            location.struct_size = sizeof location;
            EXPECT_OK(tp_store_locate(store, p, NULL, &location));
            CHECK(location.cell == 0 && location.cell_kind == TP_CELL_INNER && location.fallback == 0);
            CHECK(memcmp(location.probes, probes, sizeof probes) == 0);
            CHECK(memcmp(location.weights, weights, sizeof weights) == 0);
        }
        /* Float positions near 30 carry about 2e-6 of rounding into the local coordinates. */
        CHECK_NEAR(worst_weight, 0.0, 1e-5);
        CHECK_NEAR(worst_sh, 0.0, 1e-4);
    }
    /* Outside, without extrapolation: refused, with zero outputs. */
    world(p, 0.5, 0.5, 0.5);
    EXPECT_STATUS(tp_store_interpolate(store, p, NULL, out), TP_ERROR_OUTSIDE);
    EXPECT_STATUS(tp_store_weights(store, p, NULL, probes, weights), TP_ERROR_OUTSIDE);
    tp_store_release(store);

    /* The second golden blob has outer cells: far outside is answered from them, inside from the cell. */
    store = load_golden("tetrahedron_outer_cells_v6.bin");
    if (store) {
        static const float directions[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
        tp_location location;
        double centre[3], diagonal = 0.0;
        int d, outer_ok = 1;
        memset(&info, 0, sizeof info);
        info.struct_size = sizeof info;
        EXPECT_OK(tp_store_get_info(store, &info));
        CHECK(info.inner_cells == 1 && info.outer_cells == 4 && info.flags == 0);
        for (k = 0; k < 3; ++k) {
            centre[k] = 0.5 * ((double)info.bounds_min[k] + info.bounds_max[k]);
            diagonal += ((double)info.bounds_max[k] - info.bounds_min[k]) * (info.bounds_max[k] - info.bounds_min[k]);
        }
        diagonal = sqrt(diagonal);
        for (d = 0; d < 6; ++d) {
            double sum = 0.0;
            int slot;
            for (k = 0; k < 3; ++k) p[k] = (float)(centre[k] + 10.0 * diagonal * directions[d][k]);
            memset(&location, 0, sizeof location);
            location.struct_size = sizeof location;
            EXPECT_OK(tp_store_locate(store, p, NULL, &location));
            outer_ok &= location.cell_kind == TP_CELL_OUTER && location.t > 0.0f;
            for (slot = 0; slot < 4; ++slot) {
                outer_ok &= location.weights[slot] >= 0.0f && location.weights[slot] <= 1.0f;
                sum += location.weights[slot];
            }
            outer_ok &= fabs(sum - 1.0) < 1e-5;
            EXPECT_OK(tp_store_interpolate(store, p, NULL, out));
            for (k = 0; k < 27; ++k) outer_ok &= isfinite(out[k]) != 0;
        }
        CHECK(outer_ok);
        /* Its corners (tests/unit/test_store_blob.cpp): (0.1, -0.2, 0.05), (1.3, 0.1, -0.1), (0.2, 1.1, 0.3),
           (0.4, 0.3, 1.2); their centroid is inside. */
        p[0] = 0.5f, p[1] = 0.325f, p[2] = 0.3625f;
        memset(&location, 0, sizeof location);
        location.struct_size = sizeof location;
        EXPECT_OK(tp_store_locate(store, p, NULL, &location));
        CHECK(location.cell_kind == TP_CELL_INNER);
        tp_store_release(store);
    }
}

/* Batches against singles (packed, strided, on two threads), and every argument error of the queries. */
void test_golden_store_queries_and_errors(void) {
    enum { M = 9000 }; /* two threads each take a range of at least 4,096 queries */
    static float points[3 * M], single[27 * M], batch[27 * M], padded_points[4 * M], padded_sh[28 * M];
    static int32_t single_hints[M], batch_hints[M], padded_hints[2 * M];
    static uint32_t single_probes[4 * M], batch_probes[4 * M];
    static float single_weights[4 * M], batch_weights[4 * M];
    tp_store* store = load_golden("tiny_store_v6.bin");
    tp_batch_options options;
    tp_location location;
    tp_store_info info;
    float out[27], weights[4], inside[3], nan_point[3], outside[3];
    uint32_t probes[4];
    int32_t hint;
    int i, same = 1, padding_kept = 1;
    if (!store) return;
    for (i = 0; i < M; ++i) {
        double x = uniform01(), y = uniform01(), z = uniform01();
        if (x + y + z >= 1.0) x *= 0.3, y *= 0.3, z *= 0.3;
        world(points + 3 * i, x, y, z);
        single_hints[i] = batch_hints[i] = -1;
        EXPECT_OK(tp_store_interpolate(store, points + 3 * i, &single_hints[i], single + 27 * i));
        EXPECT_OK(tp_store_weights(store, points + 3 * i, NULL, single_probes + 4 * i, single_weights + 4 * i));
    }
    EXPECT_OK(tp_batch_options_init(&options));
    options.threads = 2;
    EXPECT_OK(tp_store_interpolate_batch(store, M, points, 0, batch_hints, 0, batch, 0, &options));
    same &= memcmp(single, batch, sizeof single) == 0 && memcmp(single_hints, batch_hints, sizeof batch_hints) == 0;
    EXPECT_OK(tp_store_weights_batch(store, M, points, 0, NULL, 0, batch_probes, 0, batch_weights, 0, &options));
    same &= memcmp(single_probes, batch_probes, sizeof batch_probes) == 0;
    same &= memcmp(single_weights, batch_weights, sizeof batch_weights) == 0;
    for (i = 0; i < M; ++i) {
        memcpy(padded_points + 4 * i, points + 3 * i, 12);
        padded_points[4 * i + 3] = -7.0f;
        padded_sh[28 * i + 27] = -7.0f;
        padded_hints[2 * i] = -1;
        padded_hints[2 * i + 1] = 12345;
    }
    EXPECT_OK(tp_store_interpolate_batch(store, M, padded_points, 16, padded_hints, 8, padded_sh, 112, NULL));
    for (i = 0; i < M; ++i) {
        same &= memcmp(padded_sh + 28 * i, single + 27 * i, 108) == 0 && padded_hints[2 * i] == 0;
        padding_kept &= padded_sh[28 * i + 27] == -7.0f && padded_hints[2 * i + 1] == 12345;
    }
    CHECK(same);
    CHECK(padding_kept);

    /* A batch with two points outside names the first and zeroes both. */
    world(points + 3 * 17, 2.0, 0.0, 0.0);
    world(points + 3 * 8500, -1.0, 0.0, 0.0); /* in the second thread's range */
    EXPECT_STATUS(tp_store_interpolate_batch(store, M, points, 0, NULL, 0, batch, 0, &options), TP_ERROR_OUTSIDE);
    CHECK(mentions_number(tp_last_error(), 17));
    CHECK(batch[27 * 17] == 0.0f && batch[27 * 8500 + 26] == 0.0f);
    EXPECT_STATUS(tp_store_weights_batch(store, M, points, 0, NULL, 0, batch_probes, 0, batch_weights, 0, NULL),
                  TP_ERROR_OUTSIDE);
    CHECK(mentions_number(tp_last_error(), 17));

    /* Argument errors: null pointers, strides too small, struct_size unset, unknown flags, NaN. */
    world(inside, 0.2, 0.2, 0.2);
    world(outside, 0.6, 0.6, 0.6);
    nan_point[0] = inside[0], nan_point[1] = (float)NAN, nan_point[2] = inside[2];
    EXPECT_STATUS(tp_store_interpolate(NULL, inside, NULL, out), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_interpolate(store, NULL, NULL, out), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_interpolate(store, inside, NULL, NULL), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_interpolate(store, nan_point, NULL, out), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_weights(NULL, inside, NULL, probes, weights), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_weights(store, inside, NULL, NULL, weights), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_weights(store, inside, NULL, probes, NULL), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_weights(store, nan_point, NULL, probes, weights), TP_ERROR_INVALID_ARGUMENT);
    memset(&location, 0, sizeof location);
    location.struct_size = sizeof location;
    EXPECT_STATUS(tp_store_locate(NULL, inside, NULL, &location), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_locate(store, NULL, NULL, &location), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_locate(store, inside, NULL, NULL), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_locate(store, nan_point, NULL, &location), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_locate(store, outside, NULL, &location), TP_ERROR_OUTSIDE);
    location.struct_size = 0;
    EXPECT_STATUS(tp_store_locate(store, inside, NULL, &location), TP_ERROR_INVALID_ARGUMENT);
    /* A foreign hint (no such cell) is never followed: refused or ignored. */
    hint = 1 << 30;
    {
        tp_status status = tp_store_interpolate(store, inside, &hint, out);
        CHECK(status == TP_OK || status == TP_ERROR_INVALID_ARGUMENT);
    }
    EXPECT_STATUS(tp_store_probe_sh(store, 5, out), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_probe_sh(store, 0, NULL), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_probe_sh(NULL, 0, out), TP_ERROR_INVALID_ARGUMENT);
    memset(&info, 0, sizeof info);
    EXPECT_STATUS(tp_store_get_info(store, &info), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_get_info(store, NULL), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_get_info(NULL, &info), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_interpolate_batch(NULL, 4, points, 0, NULL, 0, batch, 0, NULL), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_interpolate_batch(store, 4, NULL, 0, NULL, 0, batch, 0, NULL), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_interpolate_batch(store, 4, points, 0, NULL, 0, NULL, 0, NULL), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_interpolate_batch(store, 4, points, 8, NULL, 0, batch, 0, NULL), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_interpolate_batch(store, 4, points, 0, batch_hints, 2, batch, 0, NULL),
                  TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_interpolate_batch(store, 4, points, 0, NULL, 0, batch, 100, NULL), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_weights_batch(NULL, 4, points, 0, NULL, 0, batch_probes, 0, batch_weights, 0, NULL),
                  TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_weights_batch(store, 4, points, 0, NULL, 0, batch_probes, 12, batch_weights, 0, NULL),
                  TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_weights_batch(store, 4, points, 0, NULL, 0, batch_probes, 0, batch_weights, 8, NULL),
                  TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_weights_batch(store, 4, points, 0, NULL, 0, NULL, 0, batch_weights, 0, NULL),
                  TP_ERROR_INVALID_ARGUMENT);
    EXPECT_OK(tp_store_weights_batch(store, 0, NULL, 0, NULL, 0, NULL, 0, NULL, 0, NULL));
    tp_batch_options_init(&options);
    options.struct_size = 0;
    EXPECT_STATUS(tp_store_interpolate_batch(store, 4, points, 0, NULL, 0, batch, 0, &options), TP_ERROR_INVALID_ARGUMENT);
    tp_batch_options_init(&options);
    options.flags = 0x40u;
    EXPECT_STATUS(tp_store_weights_batch(store, 4, points, 0, NULL, 0, batch_probes, 0, batch_weights, 0, &options),
                  TP_ERROR_INVALID_ARGUMENT);
    memcpy(points + 3, nan_point, sizeof nan_point);
    EXPECT_STATUS(tp_store_interpolate_batch(store, 4, points, 0, NULL, 0, batch, 0, NULL), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_batch_options_init(NULL), TP_ERROR_INVALID_ARGUMENT);
    tp_store_release(store);
}

/* Files: round trips (also over an existing file and through a non-ASCII UTF-8 name), and I/O errors. */
void test_golden_store_files(void) {
    /* "harness_été_光.tpb" in UTF-8: on Windows the library must open it by its UTF-16 name. */
    static const char* const unicode_name = "harness_\xc3\xa9t\xc3\xa9_\xe5\x85\x89.tpb";
    static const char* const names[2] = {"harness_golden.tpb", NULL};
    size_t size = 0;
    unsigned char* golden = read_golden("tiny_store_v6.bin", &size);
    tp_store *store = NULL, *copy = NULL;
    const void* blob;
    size_t blob_size = 0;
    int n;
    if (!golden) return;
    EXPECT_OK(tp_store_load(golden, size, &store));
    if (!store) {
        free(golden);
        return;
    }
    for (n = 0; n < 2; ++n) {
        const char* name = names[n] ? names[n] : unicode_name;
        int round;
        for (round = 0; round < 2; ++round) { /* the second save replaces the first file */
            EXPECT_OK(tp_store_save_file(store, name));
            EXPECT_OK(tp_store_load_file(name, &copy));
            if (!copy) continue;
            EXPECT_OK(tp_store_blob(copy, &blob, &blob_size));
            CHECK(blob_size == size && memcmp(blob, golden, size) == 0);
            tp_store_release(copy);
            copy = NULL;
        }
    }
#ifdef _WIN32
    {
        /* The file carries the intended UTF-16 name (not the UTF-8 bytes read as the ANSI code page). */
        FILE* f = _wfopen(L"harness_\u00e9t\u00e9_\u5149.tpb", L"rb");
        CHECK(f != NULL);
        if (f) fclose(f);
        _wremove(L"harness_\u00e9t\u00e9_\u5149.tpb");
    }
    /* A path that is not UTF-8 names no file. */
    EXPECT_STATUS(tp_store_save_file(store, "harness_\xff\xfe.tpb"), TP_ERROR_IO);
#else
    remove(unicode_name);
#endif
    /* The load cap (tp_store_load_options): one byte below the file's size refused, at it loaded. */
    {
        tp_store_load_options options;
        EXPECT_OK(tp_store_load_options_init(&options));
        options.max_file_bytes = size - 1;
        EXPECT_STATUS(tp_store_load_file_ex(names[0], &options, &copy), TP_ERROR_IO);
        CHECK(strstr(tp_last_error(), "above the load cap") != NULL);
        options.max_file_bytes = size;
        EXPECT_OK(tp_store_load_file_ex(names[0], &options, &copy));
        tp_store_release(copy);
        copy = NULL;
    }
    remove(names[0]);

    EXPECT_STATUS(tp_store_save_file(store, "/nonexistent-dir/sub/store.tpb"), TP_ERROR_IO);
    EXPECT_STATUS(tp_store_save_file(store, "."), TP_ERROR_IO); /* a directory cannot be replaced */
    EXPECT_STATUS(tp_store_save_file(store, ""), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_save_file(store, NULL), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_save_file(NULL, names[0]), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_load_file("/nonexistent-dir/store.tpb", &copy), TP_ERROR_IO);
    CHECK(strstr(tp_last_error(), "/nonexistent-dir/store.tpb") != NULL);
    EXPECT_STATUS(tp_store_load_file(".", &copy), TP_ERROR_IO);
    CHECK(strstr(tp_last_error(), "not a regular file") != NULL);
    EXPECT_STATUS(tp_store_load_file(NULL, &copy), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_load_file(names[0], NULL), TP_ERROR_INVALID_ARGUMENT);
    CHECK(copy == NULL);
    {
        FILE* f = fopen(names[0], "wb");
        if (f) {
            fwrite(golden, 1, size - 1, f); /* a truncated store file */
            fclose(f);
            EXPECT_STATUS(tp_store_load_file(names[0], &copy), TP_ERROR_INVALID_BLOB);
            CHECK(strstr(tp_last_error(), names[0]) != NULL);
            remove(names[0]);
        }
    }
    CHECK(copy == NULL);
    EXPECT_OK(tp_store_release(NULL));
    tp_store_release(store);
    free(golden);
}

/* Every truncated prefix and every byte changed in two ways is refused (or, for bytes the loader may
   accept, loads into a store that answers finitely); another format version is a version error. */
void test_golden_store_bad_blobs(void) {
    static const char* const older[7] = {"tiny_store_v2.bin", "tetrahedron_outer_cells_v2.bin", "tiny_store_v3.bin",
                                         "tetrahedron_outer_cells_v3.bin", "tiny_store_v4.bin",
                                         "tetrahedron_outer_cells_v4.bin", "tiny_store_scene_v4.bin"};
    static const unsigned long older_version[7] = {2, 2, 3, 3, 4, 4, 4};
    size_t size = 0, cut, at;
    unsigned char* bytes = read_golden("tiny_store_v6.bin", &size);
    tp_store* store = NULL;
    int refused = 1, safe = 1, f;
    if (!bytes) return;
    for (cut = 0; cut < size; ++cut) {
        tp_status status = tp_store_load(bytes, cut, &store);
        refused &= status == TP_ERROR_INVALID_BLOB && store == NULL;
        tp_store_release(store);
        store = NULL;
    }
    CHECK(refused);
    for (at = 0; at < size; ++at) {
        static const unsigned char flips[2] = {0x01, 0xFF};
        for (f = 0; f < 2; ++f) {
            tp_status status;
            bytes[at] ^= flips[f];
            status = tp_store_load(bytes, size, &store);
            if (status == TP_OK) {
                safe = 0; /* the checksum covers every byte: nothing changed may load */
                tp_store_release(store);
                store = NULL;
            } else {
                safe &= store == NULL && (status == TP_ERROR_INVALID_BLOB || status == TP_ERROR_VERSION);
            }
            bytes[at] ^= flips[f];
        }
    }
    CHECK(safe);
    {
        unsigned char* longer = (unsigned char*)malloc(size + 1);
        if (longer) {
            memcpy(longer, bytes, size);
            longer[size] = 0;
            EXPECT_STATUS(tp_store_load(longer, size + 1, &store), TP_ERROR_INVALID_BLOB);
            free(longer);
        }
    }
    EXPECT_STATUS(tp_store_load(bytes, 0, &store), TP_ERROR_INVALID_BLOB);
    EXPECT_STATUS(tp_store_load(NULL, size, &store), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_load(bytes, size, NULL), TP_ERROR_INVALID_ARGUMENT);
    /* Another version with a consistent checksum: refused as a version, asking for a rebuild. */
    bytes[8] = 7;
    repair_checksum(bytes, size);
    EXPECT_STATUS(tp_store_load(bytes, size, &store), TP_ERROR_VERSION);
    CHECK(strstr(tp_last_error(), "rebuild") != NULL && mentions_number(tp_last_error(), 7));
    bytes[8] = 6;
    repair_checksum(bytes, size);
    EXPECT_OK(tp_store_load(bytes, size, &store));
    tp_store_release(store);
    store = NULL;
    free(bytes);
    /* Stores of formats 2, 3 and 4, as earlier libraries wrote them. */
    for (f = 0; f < 7; ++f) {
        bytes = read_golden(older[f], &size);
        if (!bytes) continue;
        EXPECT_STATUS(tp_store_load(bytes, size, &store), TP_ERROR_VERSION);
        CHECK(mentions_number(tp_last_error(), older_version[f]));
        CHECK(store == NULL);
        free(bytes);
    }
}

/* The golden store in every SH encoding, layout and position encoding: what info says, the decoded SH
   within the encoding's bound of the data (exact where it is halves), exactly that at each probe (the
   rebuilt layout's cells rebuilt when loaded). */
void test_golden_store_encodings(void) {
    static const struct {
        const char* file;
        uint32_t encoding, layout, quantized;
    } goldens[8] = {
        {"tiny_store_half_compact_quantized_v6.bin", TP_SH_ENCODING_HALF, TP_LAYOUT_COMPACT, 1},
        {"tiny_store_unorm8_fast_v6.bin", TP_SH_ENCODING_UNORM8, TP_LAYOUT_FAST, 0},
        {"tiny_store_unorm8_compact_quantized_v6.bin", TP_SH_ENCODING_UNORM8, TP_LAYOUT_COMPACT, 1},
        {"tiny_store_half_l1_fast_v6.bin", TP_SH_ENCODING_HALF_L1, TP_LAYOUT_FAST, 0},
        {"tiny_store_half_l1_compact_quantized_v6.bin", TP_SH_ENCODING_HALF_L1, TP_LAYOUT_COMPACT, 1},
        {"tiny_store_unorm8_l1_fast_quantized_v6.bin", TP_SH_ENCODING_UNORM8_L1, TP_LAYOUT_FAST, 1},
        {"tiny_store_unorm8_l1_compact_v6.bin", TP_SH_ENCODING_UNORM8_L1, TP_LAYOUT_COMPACT, 0},
        {"tiny_store_unorm8_rebuilt_quantized_v6.bin", TP_SH_ENCODING_UNORM8, TP_LAYOUT_REBUILT, 1}};
    /* The 8-bit codes' steps (sqrt(3) / 127, sqrt(15) / 2 / 127, sqrt(5) / 170) and the ratio ranges' ends. */
    static const double step[9] = {0, 0.013638195, 0.013638195, 0.013638195, 0.015247966, 0.015247966,
                                   0.013153341, 0.015247966, 0.015247966};
    static const double ratio_max[9] = {0, 1.7320508, 1.7320508, 1.7320508, 1.9364917, 1.9364917, 2.2360680, 1.9364917,
                                        1.9364917};
    int g, k;
    uint32_t j;
    for (g = 0; g < 8; ++g) {
        size_t size = 0, i;
        unsigned char* bytes = read_golden(goldens[g].file, &size);
        tp_store* store = NULL;
        tp_store_info info;
        uint64_t parts = 0;
        int within = 1, exact_at_probes = 1, l1 = goldens[g].encoding == TP_SH_ENCODING_HALF_L1 ||
                                                  goldens[g].encoding == TP_SH_ENCODING_UNORM8_L1;
        int unorm8 = goldens[g].encoding == TP_SH_ENCODING_UNORM8 || goldens[g].encoding == TP_SH_ENCODING_UNORM8_L1;
        if (!bytes) continue;
        EXPECT_OK(tp_store_load(bytes, size, &store));
        free(bytes);
        if (!store) continue;
        memset(&info, 0, sizeof info);
        info.struct_size = sizeof info;
        EXPECT_OK(tp_store_get_info(store, &info));
        CHECK(info.format_version == 6 && info.sh_encoding == goldens[g].encoding && info.layout == goldens[g].layout);
        CHECK(info.quantized_positions == goldens[g].quantized);
        CHECK(((info.flags & TP_BUILD_COMPACT) != 0) == (goldens[g].layout == TP_LAYOUT_COMPACT));
        for (i = 0; i < 16; ++i) parts += info.section_bytes[i];
        CHECK(parts == info.bytes && info.bytes == size);
        CHECK(info.section_bytes[TP_STORE_SECTION_POSITIONS] == (goldens[g].quantized ? 4u * 6u : 4u * 12u));
        CHECK(info.section_bytes[TP_STORE_SECTION_INPUT_REMAP] == 5u * 2u); /* one probe merged */
        for (k = 0; k < 3; ++k)
            CHECK(goldens[g].quantized ? info.position_step[k] > 0.0 && info.position_step[k] < 2e-5
                                       : info.position_step[k] == 0.0);
        for (j = 0; j < 5; ++j) {
            float decoded[27], out[27], p[3];
            const uint32_t stored = kProbeOfInput[j];
            EXPECT_OK(tp_store_probe_sh(store, j, decoded));
            for (k = 0; k < 27; ++k) {
                const int c = k % 9;
                const double value = golden_radiance_sh(stored, k), l0 = golden_radiance_sh(stored, k - c);
                if (l1 && c >= 4)
                    within &= decoded[k] == 0.0f;
                else if (!unorm8 || c == 0)
                    within &= decoded[k] == (float)value;
                else
                    within &= fabs(decoded[k] - value) <= l0 * (0.5 * step[c] + ratio_max[c] / 1024) * (1 + 1e-6);
            }
            /* At the probe's corner (exact in both position encodings): its decoded SH exactly. */
            world(p, stored == 1, stored == 2, stored == 3);
            EXPECT_OK(tp_store_interpolate(store, p, NULL, out));
            for (k = 0; k < 27; ++k) exact_at_probes &= out[k] == decoded[k];
        }
        CHECK(within);
        CHECK(exact_at_probes);
        tp_store_release(store);
    }
}
