/*
 * The C harness's driver: the checks, shared helpers and main(), which runs every topic (see harness.h).
 * Built twice: against the full library, and with TP_HARNESS_RUNTIME_ONLY against the run-time library
 * (natively and, in `make cross`, for Windows and aarch64). Prints "N passed, N failed" last and exits
 * non-zero on any failure. argv[1]: the repository root; the working directory is a scratch dir.
 */
#include "harness.h"

static int g_passed = 0;
static int g_failed = 0;
const char* g_repo_root = ".";

void harness_check(int ok, const char* what, const char* file, int line) {
    if (ok) {
        ++g_passed;
    } else {
        ++g_failed;
        printf("FAIL %s:%d: %s\n", file, line, what);
    }
}

void harness_check_status(tp_status got, tp_status expected, const char* call, const char* file, int line) {
    int ok = got == expected;
    if (ok && expected != TP_OK) ok = tp_last_error()[0] != '\0';
    if (!ok) {
        ++g_failed;
        printf("FAIL %s:%d: %s returned %s, expected %s (message: \"%s\")\n", file, line, call,
               tp_status_name(got), tp_status_name(expected), tp_last_error());
    } else {
        ++g_passed;
    }
}

void harness_check_fails(tp_status got, const char* call, const char* file, int line) {
    if (got != TP_OK && tp_last_error()[0] != '\0') {
        ++g_passed;
    } else {
        ++g_failed;
        printf("FAIL %s:%d: %s returned %s, expected a failure with a message\n", file, line, call,
               tp_status_name(got));
    }
}

void harness_check_near(double got, double expected, double tolerance, const char* what, const char* file,
                        int line) {
    if (fabs(got - expected) <= tolerance) {
        ++g_passed;
    } else {
        ++g_failed;
        printf("FAIL %s:%d: %s = %.9g, expected %.9g +- %.3g\n", file, line, what, got, expected, tolerance);
    }
}

/* Deterministic random numbers (xorshift64*), so failures reproduce. */
static unsigned long long g_rng = 0x9E3779B97F4A7C15ull;

double uniform01(void) {
    g_rng ^= g_rng >> 12;
    g_rng ^= g_rng << 25;
    g_rng ^= g_rng >> 27;
    return (double)((g_rng * 2685821657736338717ull) >> 11) * (1.0 / 9007199254740992.0);
}

float uniform(double lo, double hi) { return (float)(lo + (hi - lo) * uniform01()); }

double sh_tolerance(double value) { return 2e-3 * fabs(value) + 1e-4; }

/* 1 if text holds the decimal number n with no digit directly before or after it. */
int mentions_number(const char* text, unsigned long n) {
    char digits[32];
    const char* at = text;
    size_t length;
    sprintf(digits, "%lu", n);
    length = strlen(digits);
    while ((at = strstr(at, digits)) != NULL) {
        int before = at > text && at[-1] >= '0' && at[-1] <= '9';
        int after = at[length] >= '0' && at[length] <= '9';
        if (!before && !after) return 1;
        ++at;
    }
    return 0;
}

/* Weight of probe in the 4 slots (slots that repeat a probe add up). */
double weight_of(const uint32_t probes[4], const float weights[4], uint32_t probe) {
    double sum = 0.0;
    int k;
    for (k = 0; k < 4; ++k)
        if (probes[k] == probe) sum += weights[k];
    return sum;
}

/* The blob checksum of store_format.h, to forge a consistent blob: FNV-1a 64 over little-endian 64-bit
   words, each step followed by hash ^= hash >> 29 (seeded with the size, the last word zero-padded),
   the checksum field read as zero. */
#define CHECKSUM_OFFSET 104 /* formats 3 and 4: after magic, 9 uint32 (axis included), grid, origin, bounds */
void repair_checksum(unsigned char* data, size_t size) {
    uint64_t hash = 14695981039346656037ull ^ (uint64_t)size;
    size_t i, k;
    for (i = 0; i < size; i += 8) {
        uint64_t word = 0;
        for (k = 0; k < 8 && i + k < size; ++k) {
            const size_t at = i + k;
            const unsigned char byte = (at >= CHECKSUM_OFFSET && at < CHECKSUM_OFFSET + 8) ? 0 : data[at];
            word |= (uint64_t)byte << (8 * k);
        }
        hash ^= word;
        hash *= 1099511628211ull;
        hash ^= hash >> 29;
    }
    for (i = 0; i < 8; ++i) data[CHECKSUM_OFFSET + i] = (unsigned char)(hash >> (8 * i));
}

unsigned char* read_whole_file(const char* path, size_t* size) {
    FILE* f = fopen(path, "rb");
    unsigned char* bytes = NULL;
    long length;
    *size = 0;
    if (!f) return NULL;
    if (fseek(f, 0, SEEK_END) == 0 && (length = ftell(f)) >= 0 && fseek(f, 0, SEEK_SET) == 0) {
        bytes = (unsigned char*)malloc((size_t)length + 1);
        if (bytes && fread(bytes, 1, (size_t)length, f) == (size_t)length) {
            *size = (size_t)length;
        } else {
            free(bytes);
            bytes = NULL;
        }
    }
    fclose(f);
    return bytes;
}

int main(int argc, char** argv) {
    if (argc > 1) g_repo_root = argv[1];
    /* Run time: every library has these. */
    test_version_and_status_names();
    test_last_error_is_per_call();
    test_option_struct_defaults();
    test_sh_basis_functions();
    test_sh_ambient_and_directional();
    test_sh_eval_options_orders_and_windows();
    test_sh_zh3();
    test_sh_min_irradiance_and_nonnegative_window();
    test_sh_eval_options_errors();
    test_shadow_caster_volumes();
    test_golden_store_answers();
    test_golden_store_queries_and_errors();
    test_golden_store_files();
    test_golden_store_bad_blobs();
    test_golden_store_encodings();
#ifdef TP_HARNESS_RUNTIME_ONLY
    test_runtime_library_refuses_bake_time();
#else
    /* Full library: stores built here, scenes and the bake. */
    test_store_build_errors();
    test_store_build_progress();
    test_store_queries();
    test_store_info_and_struct_size();
    test_store_encodings_and_quantization();
    test_store_rebuilt_layout();
    test_store_blobs_and_files();
    test_store_without_extrapolation();
    test_batch_options();
    test_compact_layout();
    test_old_format_refused();
    test_outside_batch();
    test_small_sets();
    test_scene_and_bake();
    test_light_near_distance();
    test_scene_files();
    test_scene_import();
    test_occlusion_and_leak_control();
    test_occlusion_bake_and_blend();
    test_leak_control_queries();
    test_placement_options_and_errors();
    test_placement_whole_and_walkable();
    test_placement_playable_seeds();
    test_inside_probes();
    test_buffer_sizes_and_strides();
    test_probe_volumes();
    test_store_files();
#endif
    printf("%d passed, %d failed\n", g_passed, g_failed);
    return g_failed == 0 ? 0 : 1;
}
