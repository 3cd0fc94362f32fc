/*
 * The C harness: the public header compiled as strict C99 and linked against a shared library only.
 * One file per topic; each topic is a `void test_...(void)` declared below and called from main() in
 * harness.c. Topics marked "run time" need only the run-time library (they also run under wine and
 * qemu in `make cross`); the others build stores, scenes or bakes and need the full library.
 * Adding a topic: write topic.c, declare its functions here, call them in main(), list the file in
 * tests/CMakeLists.txt (and in TP_C_HARNESS_RUNTIME_SOURCES if it needs only the run time).
 * tests/c/check_coverage.sh fails when a tp_ function of capi/tetprobe.h is called by no topic.
 */
#ifndef TETPROBE_HARNESS_H
#define TETPROBE_HARNESS_H

#include "tetprobe.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- checks: each counts one pass or prints one failure with file and line. */
void harness_check(int ok, const char* what, const char* file, int line);
/* A call must return exactly `expected`; a failure must also leave a non-empty message. */
void harness_check_status(tp_status got, tp_status expected, const char* call, const char* file, int line);
/* A call must fail (any status but TP_OK) with a message; for cases the contract leaves open. */
void harness_check_fails(tp_status got, const char* call, const char* file, int line);
void harness_check_near(double got, double expected, double tolerance, const char* what, const char* file, int line);

#define CHECK(cond) harness_check((cond) != 0, #cond, __FILE__, __LINE__)
#define EXPECT_OK(call) harness_check_status((call), TP_OK, #call, __FILE__, __LINE__)
#define EXPECT_STATUS(call, expected) harness_check_status((call), (expected), #call, __FILE__, __LINE__)
#define EXPECT_FAILS(call) harness_check_fails((call), #call, __FILE__, __LINE__)
#define CHECK_NEAR(got, expected, tol) harness_check_near((got), (expected), (tol), #got, __FILE__, __LINE__)

/* ---- shared helpers (harness.c). */
extern const char* g_repo_root; /* argv[1]: the repository root (sample scenes, golden blobs) */
/* Deterministic random numbers (xorshift64*), so failures reproduce. */
double uniform01(void);
float uniform(double lo, double hi);
/* Half-precision SH: a relative error of 2^-11 per value, plus float rounding in the blend. */
double sh_tolerance(double value);
/* 1 if text holds the decimal number n with no digit directly before or after it. */
int mentions_number(const char* text, unsigned long n);
/* Weight of probe in the 4 slots (slots that repeat a probe add up). */
double weight_of(const uint32_t probes[4], const float weights[4], uint32_t probe);
/* Rewrites a format-3 blob's checksum so that a deliberate change is judged on its own. */
void repair_checksum(unsigned char* data, size_t size);
/* Reads a whole file (malloc'd, *size set); NULL if it cannot be read. */
unsigned char* read_whole_file(const char* path, size_t* size);

/* ---- probe clouds (cloud.c, full library). */
#define CLOUD 160
#define BIG_BATCH 10000
/* A linear field: SH coefficient k at p is a_k + b_k . p. */
float linear_field(int k, const float p[3]);
/* count probes in the cube [-1, 1]^3 with its 8 corners first (so the hull is the cube). */
void make_cloud(float* positions, float* sh, int count);
tp_store* build_cloud(float* positions, float* sh, uint32_t flags);
tp_store* build_with_flags(const float* positions, const float* sh, size_t count, uint32_t flags);
tp_store_info info_of(const tp_store* store);

/* ---- topics, run time: basics.c, sh.c, sh_options.c, volumes.c, golden_store.c. */
void test_version_and_status_names(void);
void test_last_error_is_per_call(void);
void test_option_struct_defaults(void);
void test_sh_basis_functions(void);
void test_sh_ambient_and_directional(void);
void test_sh_eval_options_orders_and_windows(void);
void test_sh_zh3(void);
void test_sh_min_irradiance_and_nonnegative_window(void);
void test_sh_eval_options_errors(void);
void test_shadow_caster_volumes(void);
void test_golden_store_answers(void);
void test_golden_store_queries_and_errors(void);
void test_golden_store_files(void);
void test_golden_store_bad_blobs(void);
void test_golden_store_encodings(void);
/* runtime_library.c: what only the run-time library does (refuse to build, bake, hold scenes). */
void test_runtime_library_refuses_bake_time(void);

/* ---- topics, full library: store_build.c, store_queries.c, store_blobs.c, batches.c, scene_bake.c. */
void test_store_build_errors(void);
void test_store_build_progress(void);
void test_store_info_and_struct_size(void);
void test_store_encodings_and_quantization(void);
void test_store_rebuilt_layout(void);
void test_small_sets(void);
void test_store_queries(void);
void test_store_without_extrapolation(void);
void test_store_blobs_and_files(void);
void test_compact_layout(void);
void test_old_format_refused(void);
void test_batch_options(void);
void test_outside_batch(void);
void test_scene_and_bake(void);
void test_light_near_distance(void);
void test_scene_files(void);
void test_scene_import(void);
/* occlusion_leak.c */
void test_occlusion_and_leak_control(void);
/* placement.c */
void test_placement_options_and_errors(void);
void test_placement_whole_and_walkable(void);
void test_placement_playable_seeds(void);
void test_inside_probes(void);
void test_occlusion_bake_and_blend(void);
void test_leak_control_queries(void);
/* buffers.c: sizes, counts and strides that overflow are refused by name; odd strides answer as packed ones. */
void test_buffer_sizes_and_strides(void);
void test_probe_volumes(void);
/* store_files.c (POSIX): load refuses non-regular and too large files; saves keep modes, follow links, clean up. */
void test_store_files(void);

#endif
