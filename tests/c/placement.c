/* Probe placement and probes inside geometry (full library): a closed room (one-sided walls facing in,
   so everything outside is solid) around a crate (one-sided faces out, so its volume is solid), lit by
   a point light. Placed probes are checked against the boxes' distances; the inside test against
   points whose side is known. */
#include "harness.h"

/* The axis-aligned box [lo, hi] as 12 one-sided triangles: outward faces out (a solid), else in (a room). */
static void add_box(tp_scene* scene, const float lo[3], const float hi[3], int outward, int two_sided) {
    static const uint32_t faces[36] = {0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5, 0, 1, 5, 0, 5, 4,
                                       2, 6, 7, 2, 7, 3, 0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6};
    float vertices[24];
    uint32_t indices[36];
    tp_material material;
    int corner, a, t;
    for (corner = 0; corner < 8; ++corner)
        for (a = 0; a < 3; ++a) vertices[3 * corner + a] = (corner & (1 << a)) ? hi[a] : lo[a];
    for (t = 0; t < 12; ++t) {
        indices[3 * t] = faces[3 * t];
        indices[3 * t + 1] = faces[3 * t + (outward ? 1 : 2)];
        indices[3 * t + 2] = faces[3 * t + (outward ? 2 : 1)];
    }
    tp_material_init(&material);
    material.albedo[0] = material.albedo[1] = material.albedo[2] = 0.6f;
    material.two_sided = two_sided;
    EXPECT_OK(tp_scene_add_mesh(scene, vertices, 8, indices, 12, &material, 1, NULL, NULL));
}

static const float kRoomLo[3] = {-3.0f, 0.0f, -3.0f}, kRoomHi[3] = {3.0f, 5.0f, 3.0f};
static const float kCrateLo[3] = {-0.5f, 1.0f, -0.5f}, kCrateHi[3] = {0.5f, 2.0f, 0.5f};

static tp_scene* room_with_crate(void) {
    tp_scene* scene = NULL;
    tp_light light;
    EXPECT_OK(tp_scene_create(&scene));
    if (!scene) return NULL;
    add_box(scene, kRoomLo, kRoomHi, 0, 0);
    add_box(scene, kCrateLo, kCrateHi, 1, 0);
    tp_light_init(&light);
    light.type = TP_LIGHT_POINT;
    light.color[0] = light.color[1] = light.color[2] = 1.0f;
    light.intensity = 20.0f;
    light.position[0] = 2.0f, light.position[1] = 2.5f, light.position[2] = 2.0f;
    EXPECT_OK(tp_scene_add_light(scene, &light, NULL));
    return scene;
}

/* Distance from p to the box [lo, hi] (0 inside it). */
static double box_distance(const float p[3], const float lo[3], const float hi[3]) {
    double sum = 0.0;
    int a;
    for (a = 0; a < 3; ++a) {
        const double d = fmax(fmax((double)lo[a] - p[a], (double)p[a] - hi[a]), 0.0);
        sum += d * d;
    }
    return sqrt(sum);
}

/* Distance from p, inside the room, to its nearest wall. */
static double wall_distance(const float p[3]) {
    double d = INFINITY;
    int a;
    for (a = 0; a < 3; ++a) d = fmin(d, fmin((double)p[a] - kRoomLo[a], (double)kRoomHi[a] - p[a]));
    return d;
}

/* Free space, at least margin from every surface (float rounding of the positions aside). */
static int free_with_margin(const float p[3], float margin) {
    const double slack = 1e-5;
    return wall_distance(p) >= margin - slack && box_distance(p, kCrateLo, kCrateHi) >= margin - slack;
}

typedef struct progress_log {
    int calls;
    int cancel_at;   /* cancel on this call (1-based), 0 = never */
    const char* cancel_stage; /* cancel at the first report of this stage, NULL = never */
    int stages_seen; /* bit 0 "candidates", 1 "bake", 2 "select" */
    int fraction_in_range;
} progress_log;

static int log_progress(void* user, float fraction, const char* stage) {
    progress_log* log = (progress_log*)user;
    ++log->calls;
    if (!(fraction >= 0.0f && fraction <= 1.0f)) log->fraction_in_range = 0;
    if (stage && strcmp(stage, "candidates") == 0) log->stages_seen |= 1;
    if (stage && strcmp(stage, "bake") == 0) log->stages_seen |= 2;
    if (stage && strcmp(stage, "select") == 0) log->stages_seen |= 4;
    if (log->cancel_stage && stage && strcmp(stage, log->cancel_stage) == 0) return 1;
    return log->cancel_at != 0 && log->calls >= log->cancel_at;
}

static tp_placement_options quick_options(void) {
    tp_placement_options options;
    tp_placement_options_init(&options);
    options.rays = 16;
    options.bounces = 1;
    options.seed = 7;
    return options;
}

void test_placement_options_and_errors(void) {
    tp_placement_options options, bad;
    tp_scene* scene = room_with_crate();
    tp_scene* empty = NULL;
    size_t bound = 99, count = 99, points = 99;
    float positions[30];
    int k;
    if (!scene) return;

    memset(&options, 0xAB, sizeof options);
    EXPECT_OK(tp_placement_options_init(&options));
    CHECK(options.struct_size == sizeof options);
    CHECK(options.mode == TP_PLACEMENT_WHOLE);
    CHECK(options.spacing == 1.0f && options.margin == 0.1f);
    CHECK(options.walk_min_height == 0.0f && options.walk_max_height == 2.0f);
    CHECK(options.target_count == 0 && options.error_bound == 0.25f);
    CHECK(options.rays == 128 && options.bounces == 2 && options.seed == 0 && options.threads == 0);
    CHECK(options.progress == NULL && options.progress_user == NULL && options.light_clearance == 1.0f);
    EXPECT_STATUS(tp_placement_options_init(NULL), TP_ERROR_INVALID_ARGUMENT);

    options = quick_options();
    EXPECT_STATUS(tp_place_probes_bound(NULL, &options, &bound), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_place_probes_bound(scene, &options, NULL), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_place_probes(NULL, &options, positions, 10, &count, NULL, 0, NULL), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_place_probes(scene, &options, NULL, 10, &count, NULL, 0, NULL), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_place_probes(scene, &options, positions, 10, NULL, NULL, 0, NULL), TP_ERROR_INVALID_ARGUMENT);

    /* Bad options: refused by the bound and by the placement alike, nothing written. */
    for (k = 0; k < 8; ++k) {
        bad = options;
        switch (k) {
            case 0: bad.spacing = 0.0f; break;
            case 1: bad.spacing = -1.0f; break;
            case 2: bad.spacing = (float)NAN; break;
            case 3: bad.mode = 7u; break;
            case 4: bad.rays = 0u; break;
            case 5: bad.rays = 1u; break; /* two half bakes need two rays */
            case 6: bad.struct_size = 4u; break;
            default: bad.margin = 100.0f; break; /* larger than the scene */
        }
        bound = 99;
        EXPECT_FAILS(tp_place_probes_bound(scene, &bad, &bound));
        positions[0] = 42.0f;
        EXPECT_FAILS(tp_place_probes(scene, &bad, positions, 10, &count, NULL, 0, &points));
        CHECK(positions[0] == 42.0f);
        if (k < 7) {
            EXPECT_STATUS(tp_place_probes_bound(scene, &bad, &bound), TP_ERROR_INVALID_ARGUMENT);
            EXPECT_STATUS(tp_place_probes(scene, &bad, positions, 10, &count, NULL, 0, &points),
                          TP_ERROR_INVALID_ARGUMENT);
        }
    }

    /* A target above the candidates: the message names both numbers. */
    EXPECT_OK(tp_place_probes_bound(scene, &options, &bound));
    bad = options;
    bad.target_count = (uint32_t)bound + 1000u;
    EXPECT_STATUS(tp_place_probes(scene, &bad, positions, 10, &count, NULL, 0, &points), TP_ERROR_INVALID_ARGUMENT);
    CHECK(mentions_number(tp_last_error(), (unsigned long)bad.target_count));
    /* A spacing that leaves fewer than 4 candidates (one lattice point over the whole room) is refused with
       the count, never a silent single probe; one that would need more than placement holds is refused too. */
    bad = options;
    bad.spacing = 1000.0f;
    bad.target_count = 1;
    EXPECT_STATUS(tp_place_probes(scene, &bad, positions, 10, &count, NULL, 0, &points), TP_ERROR_DEGENERATE);
    CHECK(strstr(tp_last_error(), "needs at least 4") != NULL);
    bad.spacing = 0.0001f;
    EXPECT_STATUS(tp_place_probes_bound(scene, &bad, &bound), TP_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(tp_last_error(), "raise the spacing") != NULL);
    /* A caller built before light_clearance (its struct ends before it) gets the default. */
    bad = options;
    bad.struct_size = (uint32_t)offsetof(tp_placement_options, light_clearance);
    bad.light_clearance = -5.0f; /* beyond the caller's struct: never read */
    EXPECT_OK(tp_place_probes_bound(scene, &bad, &bound));
    bad = options;
    bad.light_clearance = -1.0f;
    bad.target_count = 8;
    bad.error_bound = 0.0f;
    EXPECT_STATUS(tp_place_probes(scene, &bad, positions, 10, &count, NULL, 0, &points), TP_ERROR_INVALID_ARGUMENT);

    /* No mesh: nothing can be inside, nothing decided. */
    EXPECT_OK(tp_scene_create(&empty));
    if (empty) {
        float probe[3] = {0.0f, 0.0f, 0.0f};
        uint32_t inside[1];
        EXPECT_STATUS(tp_place_probes(empty, &options, positions, 10, &count, NULL, 0, &points), TP_ERROR_SCENE);
        EXPECT_STATUS(tp_find_inside_probes(empty, probe, 0, 1, inside, 1, &count), TP_ERROR_SCENE);
        /* An open two-sided sheet has no solid side either. */
        {
            static const float sheet[12] = {-1, 0, -1, 1, 0, -1, 1, 0, 1, -1, 0, 1};
            static const uint32_t quads[6] = {0, 2, 1, 0, 3, 2};
            tp_material material;
            tp_material_init(&material);
            material.two_sided = 1;
            EXPECT_OK(tp_scene_add_mesh(empty, sheet, 4, quads, 2, &material, 1, NULL, NULL));
            EXPECT_STATUS(tp_find_inside_probes(empty, probe, 0, 1, inside, 1, &count), TP_ERROR_SCENE);
            EXPECT_STATUS(tp_fix_inside_probes(empty, probe, 0, 1, TP_INSIDE_DROP, 0.1f, probe, 1, &count),
                          TP_ERROR_SCENE);
            EXPECT_STATUS(tp_place_probes(empty, &options, positions, 10, &count, NULL, 0, &points), TP_ERROR_SCENE);
        }
        tp_scene_release(empty);
    }
    tp_scene_release(scene);
}

void test_placement_whole_and_walkable(void) {
    tp_scene* scene = room_with_crate();
    tp_placement_options options;
    size_t bound = 0, count = 0, points = 0, again_count = 0, again_points = 0, i;
    float *positions, *curve, *again, *again_curve;
    uint32_t inside[1];
    size_t inside_count = 99;
    progress_log log;
    if (!scene) return;

    options = quick_options();
    options.error_bound = 0.6f; /* reached well before all candidates (the lamp's falloff keeps 0.4 with all) */
    memset(&log, 0, sizeof log);
    log.fraction_in_range = 1;
    options.progress = log_progress;
    options.progress_user = &log;
    EXPECT_OK(tp_place_probes_bound(scene, &options, &bound));
    CHECK(bound >= 4);
    positions = (float*)malloc(3 * sizeof(float) * (bound + 1));
    again = (float*)malloc(3 * sizeof(float) * (bound + 1));
    curve = (float*)malloc(2 * sizeof(float) * (bound + 1));
    again_curve = (float*)malloc(2 * sizeof(float) * (bound + 1));
    if (!positions || !again || !curve || !again_curve) {
        CHECK(!"allocation");
        return;
    }

    EXPECT_OK(tp_place_probes(scene, &options, positions, bound, &count, curve, bound, &points));
    CHECK(count >= 4 && count <= bound);
    CHECK(log.calls > 0 && log.fraction_in_range && (log.stages_seen & 1) != 0);
    /* Every probe in free space, at least the margin from the walls and the crate. */
    for (i = 0; i < count; ++i) CHECK(free_with_margin(positions + 3 * i, options.margin));
    EXPECT_OK(tp_find_inside_probes(scene, positions, 0, count, inside, 1, &inside_count));
    CHECK(inside_count == 0);
    /* The error curve: one point per round, counts increasing, ending at the placement, which meets the
       bound (the error of fewer probes did not). */
    CHECK(points >= 1 && points <= bound);
    if (points >= 1) {
        CHECK(curve[2 * (points - 1)] == (float)count);
        CHECK(curve[2 * (points - 1) + 1] <= options.error_bound);
        for (i = 0; i < points; ++i) CHECK(curve[2 * i + 1] >= 0.0f);
        for (i = 1; i < points; ++i) CHECK(curve[2 * i] > curve[2 * (i - 1)]);
        if (points >= 2) CHECK(curve[2 * (points - 2) + 1] > options.error_bound);
    }

    /* The same seed gives the same bytes, whatever the thread count. */
    options.progress = NULL;
    options.threads = 1;
    EXPECT_OK(tp_place_probes(scene, &options, again, bound, &again_count, again_curve, bound, &again_points));
    CHECK(again_count == count && again_points == points);
    CHECK(again_count == count && memcmp(again, positions, 3 * sizeof(float) * count) == 0);
    CHECK(again_points == points && memcmp(again_curve, curve, 2 * sizeof(float) * points) == 0);
    options.threads = 2;
    EXPECT_OK(tp_place_probes(scene, &options, again, bound, &again_count, NULL, 0, NULL));
    CHECK(again_count == count && memcmp(again, positions, 3 * sizeof(float) * count) == 0);

    /* Too small a buffer: the counts are reported and nothing is written. */
    if (count >= 2) {
        again[0] = 42.0f;
        EXPECT_STATUS(tp_place_probes(scene, &options, again, count - 1, &again_count, NULL, 0, &again_points),
                      TP_ERROR_BUFFER_TOO_SMALL);
        CHECK(again_count == count && again_points == points && again[0] == 42.0f);
        if (points >= 2) {
            again_curve[0] = 42.0f;
            EXPECT_STATUS(tp_place_probes(scene, &options, again, bound, &again_count, again_curve, points - 1,
                                          &again_points),
                          TP_ERROR_BUFFER_TOO_SMALL);
            CHECK(again_count == count && again_points == points && again_curve[0] == 42.0f);
        }
    }

    /* A target without an error bound: exactly that many probes, still in free space. A smaller target gets
       its own set after the same greedy rounds (16 and 20 on the way to 25 and 30): its curve before the
       last point is the larger target's first points, bit for bit. */
    options.error_bound = 0.0f;
    options.target_count = 30;
    EXPECT_OK(tp_place_probes(scene, &options, positions, bound, &count, curve, bound, &points));
    CHECK(count == 30 && points >= 3 && curve[2 * (points - 1)] == 30.0f);
    for (i = 0; i < count && i < 30; ++i) CHECK(free_with_margin(positions + 3 * i, options.margin));
    options.target_count = 25;
    EXPECT_OK(tp_place_probes(scene, &options, again, bound, &again_count, again_curve, bound, &again_points));
    CHECK(again_count == 25 && again_points >= 2 && again_curve[2 * (again_points - 1)] == 25.0f);
    for (i = 0; i < again_count && i < 25; ++i) CHECK(free_with_margin(again + 3 * i, options.margin));
    CHECK(again_points >= 2 && again_points <= points &&
          memcmp(again_curve, curve, 2 * sizeof(float) * (again_points - 1)) == 0);
    /* Neither: nothing is chosen or baked, every candidate returned, no curve. */
    options.target_count = 0;
    EXPECT_OK(tp_place_probes(scene, &options, again, bound, &again_count, again_curve, bound, &again_points));
    CHECK(again_count > 20 && again_count <= bound && again_points == 0);

    /* Cancelled at the first report: TP_ERROR_CANCELLED, nothing written. */
    memset(&log, 0, sizeof log);
    log.cancel_at = 1;
    options.progress = log_progress;
    options.progress_user = &log;
    again[0] = 42.0f;
    again_curve[0] = 42.0f;
    EXPECT_STATUS(tp_place_probes(scene, &options, again, bound, &again_count, again_curve, bound, &again_points),
                  TP_ERROR_CANCELLED);
    CHECK(log.calls == 1 && again[0] == 42.0f && again_curve[0] == 42.0f);
    /* ... and later, while choosing. */
    options.error_bound = 0.0f;
    options.target_count = 20;
    memset(&log, 0, sizeof log);
    EXPECT_OK(tp_place_probes(scene, &options, again, bound, &again_count, NULL, 0, NULL));
    CHECK((log.stages_seen & 7) == 7);
    memset(&log, 0, sizeof log);
    log.cancel_stage = "select";
    again[0] = 42.0f;
    again_curve[0] = 42.0f;
    EXPECT_STATUS(tp_place_probes(scene, &options, again, bound, &again_count, again_curve, bound, &again_points),
                  TP_ERROR_CANCELLED);
    CHECK(again[0] == 42.0f && again_curve[0] == 42.0f);

    /* Walkable: probes stand in the band [0, 2] above an upward-facing surface, here the room's floor
       (y = 0) or the crate's top (y = 2, over the crate's footprint; the room is 5 high so that this
       band stays inside it). */
    options = quick_options();
    options.mode = TP_PLACEMENT_WALKABLE;
    options.error_bound = 0.0f;
    EXPECT_OK(tp_place_probes_bound(scene, &options, &bound));
    free(again);
    again = (float*)malloc(3 * sizeof(float) * (bound + 1));
    if (again) {
        EXPECT_OK(tp_place_probes(scene, &options, again, bound, &again_count, NULL, 0, NULL));
        int on_crate = 0;
        CHECK(again_count > 0);
        for (i = 0; i < again_count; ++i) {
            const float* p = again + 3 * i;
            const int over_crate = fabs(p[0]) <= 0.5f && fabs(p[2]) <= 0.5f;
            CHECK(free_with_margin(p, options.margin));
            CHECK((p[1] >= 0.0f && p[1] <= 2.0f) || (over_crate && p[1] >= 2.0f && p[1] <= 4.0f));
            on_crate += over_crate && p[1] > 2.0f;
        }
        CHECK(on_crate > 0);
    }
    free(positions);
    free(again);
    free(curve);
    free(again_curve);
    tp_scene_release(scene);
}

void test_placement_playable_seeds(void) {
    tp_scene* scene = room_with_crate();
    tp_placement_options options;
    size_t bound = 0, all = 0, count = 0;
    float* positions;
    static const float inside_room[6] = {2.0f, 0.5f, -2.0f, -2.0f, 0.5f, 2.0f};
    static const float outside[3] = {50.0f, 0.5f, 50.0f};
    if (!scene) return;
    options = quick_options();
    options.mode = TP_PLACEMENT_WALKABLE;
    options.error_bound = 0.0f;
    EXPECT_OK(tp_place_probes_bound(scene, &options, &bound));
    positions = (float*)malloc(3 * sizeof(float) * (bound + 1));
    if (!positions) {
        CHECK(!"allocation");
        return;
    }
    EXPECT_OK(tp_place_probes(scene, &options, positions, bound, &all, NULL, 0, NULL));
    /* Seeds on the floor: the floor and the crate's top are connected through free space (the crate is
       1 high, the band 2), so every candidate is kept. */
    EXPECT_OK(tp_scene_set_playable_seeds(scene, inside_room, 2));
    EXPECT_OK(tp_place_probes(scene, &options, positions, bound, &count, NULL, 0, NULL));
    CHECK(count == all && count > 0);
    /* A seed that sees no candidate: a clear status naming the seeds. */
    EXPECT_OK(tp_scene_set_playable_seeds(scene, outside, 1));
    EXPECT_STATUS(tp_place_probes(scene, &options, positions, bound, &count, NULL, 0, NULL), TP_ERROR_SCENE);
    CHECK(strstr(tp_last_error(), "playable seeds") != NULL && mentions_number(tp_last_error(), 1));
    /* Cleared: all candidates again. */
    EXPECT_OK(tp_scene_set_playable_seeds(scene, NULL, 0));
    EXPECT_OK(tp_place_probes(scene, &options, positions, bound, &count, NULL, 0, NULL));
    CHECK(count == all);
    EXPECT_STATUS(tp_scene_set_playable_seeds(NULL, inside_room, 2), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_scene_set_playable_seeds(scene, NULL, 2), TP_ERROR_INVALID_ARGUMENT);
    free(positions);
    tp_scene_release(scene);
}

void test_inside_probes(void) {
    tp_scene* scene = room_with_crate();
    /* 4 floats per probe: 1 and 3 are inside the crate, 0 and 2 in the room. */
    float strided[16] = {2.0f, 1.5f, 2.0f, -1.0f, 0.0f, 1.5f, 0.0f, -1.0f,
                         -2.0f, 0.5f, 1.0f, -1.0f, 0.2f, 1.2f, -0.3f, -1.0f};
    float packed[12], out[12];
    uint32_t inside[4] = {99, 99, 99, 99};
    size_t count = 99, i;
    if (!scene) return;
    for (i = 0; i < 4; ++i) memcpy(packed + 3 * i, strided + 4 * i, 3 * sizeof(float));

    EXPECT_OK(tp_find_inside_probes(scene, strided, 16, 4, inside, 4, &count));
    CHECK(count == 2 && inside[0] == 1 && inside[1] == 3 && inside[2] == 99);
    inside[0] = 99;
    EXPECT_STATUS(tp_find_inside_probes(scene, strided, 16, 4, inside, 1, &count), TP_ERROR_BUFFER_TOO_SMALL);
    CHECK(count == 2 && inside[0] == 99);
    EXPECT_OK(tp_find_inside_probes(scene, NULL, 0, 0, NULL, 0, &count));
    CHECK(count == 0);
    EXPECT_STATUS(tp_find_inside_probes(NULL, packed, 0, 4, inside, 4, &count), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_find_inside_probes(scene, NULL, 0, 4, inside, 4, &count), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_find_inside_probes(scene, packed, 0, 4, inside, 4, NULL), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_find_inside_probes(scene, packed, 0, 4, NULL, 4, &count), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_find_inside_probes(scene, packed, 8, 4, inside, 4, &count), TP_ERROR_INVALID_ARGUMENT);

    /* The effects plan counts and names them. */
    {
        tp_effects_plan plan;
        tp_bake_options bake;
        char text[512];
        tp_bake_options_init(&bake);
        memset(&plan, 0, sizeof plan);
        plan.struct_size = sizeof plan;
        EXPECT_OK(tp_bake_plan(scene, strided, 16, 4, &bake, &plan, text, sizeof text));
        CHECK(plan.inside_probes == 2);
        CHECK(strstr(text, "inside geometry: 2 probes (1, 3)") != NULL);
        EXPECT_OK(tp_bake_plan(scene, strided, 32, 2, &bake, &plan, text, sizeof text)); /* probes 0 and 2 */
        CHECK(plan.inside_probes == 0 && strstr(text, "inside geometry") == NULL);
        /* A caller compiled before the field: only struct_size bytes are written. */
        plan.struct_size = (uint32_t)offsetof(tp_effects_plan, inside_probes);
        plan.inside_probes = 77;
        EXPECT_OK(tp_bake_plan(scene, strided, 16, 4, &bake, &plan, text, sizeof text));
        CHECK(plan.inside_probes == 77);
    }

    /* Drop: the free probes, in their order; in place over packed positions. */
    memcpy(out, packed, sizeof packed);
    EXPECT_OK(tp_fix_inside_probes(scene, out, 0, 4, TP_INSIDE_DROP, 0.1f, out, 4, &count));
    CHECK(count == 2 && memcmp(out, packed, 3 * sizeof(float)) == 0 &&
          memcmp(out + 3, packed + 6, 3 * sizeof(float)) == 0);
    /* Push: every probe, the free ones unchanged, the inside ones moved out by at least the margin. */
    EXPECT_OK(tp_fix_inside_probes(scene, strided, 16, 4, TP_INSIDE_PUSH, 0.1f, out, 4, &count));
    CHECK(count == 4);
    CHECK(memcmp(out, packed, 3 * sizeof(float)) == 0 && memcmp(out + 6, packed + 6, 3 * sizeof(float)) == 0);
    CHECK(free_with_margin(out + 3, 0.1f) && free_with_margin(out + 9, 0.1f));
    EXPECT_OK(tp_find_inside_probes(scene, out, 0, 4, inside, 4, &count));
    CHECK(count == 0);

    /* Errors: an unknown mode, too small a buffer, a probe that cannot be pushed out (no point of the
       room is 10 from every wall); nothing written. */
    out[0] = 42.0f;
    EXPECT_STATUS(tp_fix_inside_probes(scene, packed, 0, 4, 2u, 0.1f, out, 4, &count), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_fix_inside_probes(scene, packed, 0, 4, TP_INSIDE_DROP, 0.1f, out, 1, &count),
                  TP_ERROR_BUFFER_TOO_SMALL);
    CHECK(count == 2 && out[0] == 42.0f);
    EXPECT_STATUS(tp_fix_inside_probes(scene, packed, 0, 4, TP_INSIDE_PUSH, 10.0f, out, 4, &count), TP_ERROR_SCENE);
    CHECK(out[0] == 42.0f && mentions_number(tp_last_error(), 1));
    EXPECT_STATUS(tp_fix_inside_probes(NULL, packed, 0, 4, TP_INSIDE_DROP, 0.1f, out, 4, &count),
                  TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_fix_inside_probes(scene, packed, 0, 4, TP_INSIDE_DROP, 0.1f, out, 4, NULL),
                  TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_fix_inside_probes(scene, packed, 0, 4, TP_INSIDE_DROP, 0.1f, NULL, 4, &count),
                  TP_ERROR_INVALID_ARGUMENT);
    packed[4] = (float)NAN;
    EXPECT_STATUS(tp_fix_inside_probes(scene, packed, 0, 4, TP_INSIDE_DROP, 0.1f, out, 4, &count),
                  TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_find_inside_probes(scene, packed, 0, 4, inside, 4, &count), TP_ERROR_INVALID_ARGUMENT);
    tp_scene_release(scene);
}
