/* Scenes, scene files and the bake (full library). */
#include "harness.h"

static int cancel_bake(void* user, float fraction, const char* stage) {
    int* calls = (int*)user;
    (void)fraction;
    (void)stage;
    ++*calls;
    return 1;
}

void test_scene_and_bake(void) {
    tp_scene* scene = NULL;
    const float sky[3] = {0.5f, 0.25f, 1.0f};
    float positions[6] = {0, 0, 0, 3, -0.5f, 2};
    float baked[54], expected[27];
    const float* listed = NULL;
    size_t listed_count = 0;
    tp_bake_options options;
    tp_effects_plan plan;
    char text[256];
    int k, p;

    EXPECT_OK(tp_scene_release(NULL));
    EXPECT_STATUS(tp_scene_create(NULL), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_OK(tp_scene_create(&scene));
    if (!scene) return;

    /* Uniform sky, nothing else: every probe holds exactly the constant-radiance SH. */
    EXPECT_OK(tp_scene_set_sky_color(scene, sky));
    EXPECT_OK(tp_scene_set_probes(scene, positions, 2));
    EXPECT_OK(tp_scene_probes(scene, &listed, &listed_count));
    CHECK(listed_count == 2 && listed != NULL && memcmp(listed, positions, sizeof positions) == 0);
    tp_bake_options_init(&options);
    options.rays = 64;
    options.bounces = 1;
    memset(&plan, 0, sizeof plan);
    plan.struct_size = sizeof plan;
    text[0] = '\0';
    EXPECT_OK(tp_bake_plan(scene, positions, 0, 2, &options, &plan, text, sizeof text));
    CHECK(plan.sky == 1);
    CHECK(plan.lights == 0 && plan.direct_lights == 0 && plan.meshes == 0);
    CHECK(plan.bounces == 0); /* nothing to bounce off */
    CHECK(strlen(text) > 0 && strstr(text, "sky") != NULL);
    EXPECT_OK(tp_bake(scene, positions, 0, 2, &options, baked, 0));
    memset(expected, 0, sizeof expected);
    tp_sh_add_ambient(expected, sky);
    for (p = 0; p < 2; ++p)
        for (k = 0; k < 27; ++k) CHECK_NEAR(baked[27 * p + k], expected[k], 1e-3 * expected[k - k % 9] + 1e-4);

    /* The same through an SH sky. */
    EXPECT_OK(tp_scene_set_sky_sh(scene, expected));
    EXPECT_OK(tp_bake(scene, positions, 0, 2, &options, baked, 0));
    for (k = 0; k < 27; ++k) CHECK_NEAR(baked[k], expected[k], 1e-3 * expected[k - k % 9] + 1e-4);

    /* A floor and a directional sun: the plan counts them; baking with a strided output works. */
    {
        static const float floor_vertices[12] = {-10, -1, -10, 10, -1, -10, 10, -1, 10, -10, -1, 10};
        static const uint32_t floor_indices[6] = {0, 2, 1, 0, 3, 2};
        static const uint32_t bad_indices[6] = {0, 2, 1, 0, 3, 9};
        float nan_vertices[12];
        tp_material material;
        tp_light sun;
        uint32_t mesh_id = 99, light_id = 99;
        float strided[2 * 30];
        const float black[3] = {0, 0, 0};
        float up[3] = {0, 1, 0}, irradiance[3];
        int calls = 0;
        tp_material_init(&material);
        material.albedo[0] = material.albedo[1] = material.albedo[2] = 0.5f;
        EXPECT_OK(tp_scene_add_mesh(scene, floor_vertices, 4, floor_indices, 2, &material, 1, NULL, &mesh_id));
        CHECK(mesh_id == 0);
        tp_light_init(&sun);
        sun.type = TP_LIGHT_DIRECTIONAL;
        sun.direction[0] = 0.0f, sun.direction[1] = -1.0f, sun.direction[2] = 0.0f;
        sun.color[0] = sun.color[1] = sun.color[2] = 1.0f;
        sun.intensity = 2.0f;
        EXPECT_OK(tp_scene_add_light(scene, &sun, &light_id));
        CHECK(light_id == 0);
        EXPECT_OK(tp_scene_set_sky_color(scene, black));
        EXPECT_OK(tp_bake_plan(scene, positions, 0, 2, &options, &plan, NULL, 0));
        CHECK(plan.lights == 1 && plan.direct_lights == 1 && plan.meshes == 1 && plan.sky == 0);
        CHECK(plan.bounces == 1);
        for (k = 0; k < 60; ++k) strided[k] = -3.0f;
        EXPECT_OK(tp_bake(scene, positions, 0, 2, &options, strided, 120));
        CHECK(strided[27] == -3.0f && strided[59] == -3.0f);
        /* Facing the sun: its direct irradiance (with the L2 overshoot, 1.0625 E) plus light from the floor. */
        EXPECT_OK(tp_sh_eval_irradiance(strided, up, irradiance));
        CHECK(irradiance[0] > 2.0f && irradiance[0] < 2.5f);

        /* Culling of shadow casters changes nothing in the result. */
        options.flags = TP_BAKE_NO_CULLING;
        EXPECT_OK(tp_bake(scene, positions, 0, 2, &options, baked, 0));
        CHECK(memcmp(baked, strided, 108) == 0);
        options.flags = 0;

        options.progress = cancel_bake;
        options.progress_user = &calls;
        EXPECT_STATUS(tp_bake(scene, positions, 0, 2, &options, baked, 0), TP_ERROR_CANCELLED);
        CHECK(calls >= 1);
        options.progress = NULL;

        /* Errors: naming what is wrong, nothing added. */
        memcpy(nan_vertices, floor_vertices, sizeof nan_vertices);
        nan_vertices[4] = (float)NAN;
        EXPECT_FAILS(tp_scene_add_mesh(scene, floor_vertices, 4, bad_indices, 2, &material, 1, NULL, &mesh_id));
        EXPECT_FAILS(tp_scene_add_mesh(scene, nan_vertices, 4, floor_indices, 2, &material, 1, NULL, &mesh_id));
        EXPECT_STATUS(tp_scene_add_mesh(NULL, floor_vertices, 4, floor_indices, 2, &material, 1, NULL, &mesh_id),
                      TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_scene_add_mesh(scene, NULL, 4, floor_indices, 2, &material, 1, NULL, &mesh_id),
                      TP_ERROR_INVALID_ARGUMENT);
        sun.intensity = -1.0f;
        EXPECT_FAILS(tp_scene_add_light(scene, &sun, &light_id));
        sun.intensity = 1.0f;
        sun.type = 42u;
        EXPECT_FAILS(tp_scene_add_light(scene, &sun, &light_id));
        EXPECT_STATUS(tp_scene_add_light(scene, NULL, &light_id), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_OK(tp_bake_plan(scene, positions, 0, 2, &options, &plan, NULL, 0));
        CHECK(plan.lights == 1 && plan.meshes == 1);
    }

    EXPECT_STATUS(tp_scene_set_sky_color(NULL, sky), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_scene_set_sky_color(scene, NULL), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_scene_set_sky_sh(scene, NULL), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_scene_probes(NULL, &listed, &listed_count), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_scene_set_probes(scene, NULL, 2), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_bake(NULL, positions, 0, 2, &options, baked, 0), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_bake(scene, NULL, 0, 2, &options, baked, 0), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_bake(scene, positions, 0, 2, &options, NULL, 0), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_bake(scene, positions, 4, 2, &options, baked, 0), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_FAILS(tp_bake(scene, positions, 0, 0, &options, baked, 0));
    EXPECT_STATUS(tp_bake_plan(NULL, positions, 0, 2, &options, &plan, NULL, 0), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_bake_plan(scene, positions, 0, 2, &options, NULL, NULL, 0), TP_ERROR_INVALID_ARGUMENT);
    /* A summary that does not fit its buffer, unset struct sizes, no materials. */
    {
        char small[8];
        const float black[3] = {0, 0, 0};
        static const float tri[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
        static const uint32_t tri_indices[3] = {0, 1, 2};
        tp_material material;
        uint32_t mesh_id = 77;
        EXPECT_OK(tp_scene_set_sky_color(scene, black));
        memset(&plan, 0, sizeof plan);
        plan.struct_size = sizeof plan;
        EXPECT_STATUS(tp_bake_plan(scene, positions, 0, 2, &options, &plan, small, sizeof small),
                      TP_ERROR_BUFFER_TOO_SMALL);
        CHECK(small[0] == '\0');
        plan.struct_size = 0;
        EXPECT_STATUS(tp_bake_plan(scene, positions, 0, 2, &options, &plan, NULL, 0), TP_ERROR_INVALID_ARGUMENT);
        options.struct_size = 0;
        EXPECT_STATUS(tp_bake(scene, positions, 0, 2, &options, baked, 0), TP_ERROR_INVALID_ARGUMENT);
        tp_bake_options_init(&options);
        tp_material_init(&material);
        EXPECT_STATUS(tp_scene_add_mesh(scene, tri, 3, tri_indices, 1, &material, 0, NULL, &mesh_id),
                      TP_ERROR_INVALID_ARGUMENT);
    }
    options.rays = 0;
    EXPECT_STATUS(tp_bake(scene, positions, 0, 2, &options, baked, 0), TP_ERROR_INVALID_ARGUMENT);
    tp_bake_options_init(&options);
    positions[4] = (float)NAN;
    EXPECT_STATUS(tp_bake(scene, positions, 0, 2, &options, baked, 0), TP_ERROR_INVALID_ARGUMENT);
    tp_scene_release(scene);
}

/* A point light's near distance: closer than it the irradiance is the one at that distance; a negative
   distance is refused with a message naming it. */
void test_light_near_distance(void) {
    static const float floor_vertices[12] = {-10, -5, -10, 10, -5, -10, 10, -5, 10, -10, -5, 10};
    static const uint32_t floor_indices[6] = {0, 2, 1, 0, 3, 2};
    const float probe[3] = {0.2f, 0, 0}, towards_light[3] = {-1, 0, 0};
    float near_sh[27], far_sh[27], near_e[3], far_e[3];
    tp_scene* plain = NULL;
    tp_scene* clamped = NULL;
    tp_material material;
    tp_light light;
    tp_bake_options options;
    uint32_t id = 0;
    EXPECT_OK(tp_scene_create(&plain));
    EXPECT_OK(tp_scene_create(&clamped));
    if (!plain || !clamped) goto done;
    tp_material_init(&material);
    EXPECT_OK(tp_scene_add_mesh(plain, floor_vertices, 4, floor_indices, 2, &material, 1, NULL, &id));
    EXPECT_OK(tp_scene_add_mesh(clamped, floor_vertices, 4, floor_indices, 2, &material, 1, NULL, &id));
    tp_light_init(&light);
    CHECK(light.near_distance == 0.0f);
    light.type = TP_LIGHT_POINT;
    light.intensity = 1.0f;
    EXPECT_OK(tp_scene_add_light(plain, &light, &id));
    light.near_distance = 0.5f;
    EXPECT_OK(tp_scene_add_light(clamped, &light, &id));
    tp_bake_options_init(&options);
    options.rays = 16;
    options.bounces = 0;
    EXPECT_OK(tp_bake(plain, probe, 0, 1, &options, far_sh, 0));
    EXPECT_OK(tp_bake(clamped, probe, 0, 1, &options, near_sh, 0));
    EXPECT_OK(tp_sh_eval_irradiance(far_sh, towards_light, far_e));
    EXPECT_OK(tp_sh_eval_irradiance(near_sh, towards_light, near_e));
    /* Direct light only, no noise: the ratio is (0.5 / 0.2)^2. */
    CHECK(near_e[0] > 0.0f);
    CHECK_NEAR(far_e[0] / near_e[0], 6.25f, 1e-3f);
    light.near_distance = -1.0f;
    EXPECT_STATUS(tp_scene_add_light(clamped, &light, &id), TP_ERROR_SCENE);
    CHECK(strstr(tp_last_error(), "near distance") != NULL);
done:
    tp_scene_release(plain);
    tp_scene_release(clamped);
}

void test_scene_files(void) {
    tp_scene* scene = NULL;
    char path[1024];
    const char* bad_path = "harness_bad_scene.json";
    static const char* const samples[] = {"cornell_box.json", "two_rooms.json", "race_track.json"};
    size_t i;
    FILE* f;
    EXPECT_STATUS(tp_scene_load_file(NULL, &scene), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_FAILS(tp_scene_load_file("/nonexistent-dir/scene.json", &scene));
    f = fopen(bad_path, "w");
    if (f) {
        fputs("{ \"meshes\": [ { \"vertices\": [1, 2,", f);
        fclose(f);
        EXPECT_STATUS(tp_scene_load_file(bad_path, &scene), TP_ERROR_SCENE);
        CHECK(strstr(tp_last_error(), bad_path) != NULL);
        remove(bad_path);
    }
    CHECK(scene == NULL);
    /* The sample scenes of the repository that are present: each loads, lists probes, plans. */
    for (i = 0; i < sizeof samples / sizeof samples[0]; ++i) {
        sprintf(path, "%.900s/samples/scenes/%s", g_repo_root, samples[i]);
        const float* probes = NULL;
        size_t count = 0;
        tp_effects_plan plan;
        f = fopen(path, "r");
        if (!f) continue;
        fclose(f);
        EXPECT_OK(tp_scene_load_file(path, &scene));
        if (scene) {
            EXPECT_OK(tp_scene_probes(scene, &probes, &count));
            CHECK(count > 0);
            memset(&plan, 0, sizeof plan);
            plan.struct_size = sizeof plan;
            EXPECT_OK(tp_bake_plan(scene, probes, 0, count, NULL, &plan, NULL, 0));
            CHECK(plan.meshes > 0);
            tp_scene_release(scene);
            scene = NULL;
        }
    }
}

/* Scene files through Assimp: load options, the scene's up, the import's notes, bad files. */
void test_scene_import(void) {
    tp_scene* scene = NULL;
    tp_scene_load_options options;
    char path[1024];
    char notes[512];
    size_t size = 0;
    uint32_t up = 0;
    FILE* f;

    EXPECT_STATUS(tp_scene_load_options_init(NULL), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_OK(tp_scene_load_options_init(&options));
    CHECK(options.struct_size == sizeof options && options.up == TP_UP_FILE && options.scale == 0.0f);

    /* The sample glTF: y-up metres by default, no notes; the options override the up and the unit. */
    sprintf(path, "%.900s/samples/scenes/two_rooms.gltf", g_repo_root);
    EXPECT_OK(tp_scene_load_file_ex(path, NULL, &scene));
    if (scene) {
        const float* probes = NULL;
        size_t count = 99;
        EXPECT_OK(tp_scene_up(scene, &up));
        CHECK(up == TP_UP_POS_Y);
        EXPECT_OK(tp_scene_notes(scene, NULL, 0, &size));
        CHECK(size == 1);
        EXPECT_OK(tp_scene_probes(scene, &probes, &count));
        CHECK(count == 0); /* glTF has no probes */
        EXPECT_STATUS(tp_scene_up(scene, NULL), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_OK(tp_scene_set_up(scene, TP_UP_NEG_Z));
        EXPECT_OK(tp_scene_up(scene, &up));
        CHECK(up == TP_UP_NEG_Z);
        EXPECT_STATUS(tp_scene_set_up(scene, TP_UP_FILE), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_scene_set_up(scene, 7u), TP_ERROR_INVALID_ARGUMENT);
        tp_scene_release(scene);
        scene = NULL;
    }
    options.up = TP_UP_POS_Z;
    options.scale = 2.0f;
    EXPECT_OK(tp_scene_load_file_ex(path, &options, &scene));
    if (scene) {
        EXPECT_OK(tp_scene_up(scene, &up));
        CHECK(up == TP_UP_POS_Z);
        tp_scene_release(scene);
        scene = NULL;
    }
    options.scale = -1.0f;
    EXPECT_STATUS(tp_scene_load_file_ex(path, &options, &scene), TP_ERROR_INVALID_ARGUMENT);
    tp_scene_load_options_init(&options);
    options.up = 9u;
    EXPECT_STATUS(tp_scene_load_file_ex(path, &options, &scene), TP_ERROR_INVALID_ARGUMENT);
    options.struct_size = 0;
    EXPECT_STATUS(tp_scene_load_file_ex(path, &options, &scene), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_scene_load_file_ex(NULL, NULL, &scene), TP_ERROR_INVALID_ARGUMENT);
    CHECK(scene == NULL);

    /* An OBJ without a material takes the default one, and the notes say so; the text comes whole or
       not at all (BUFFER_TOO_SMALL with the size it needs). */
    f = fopen("harness_bare.obj", "w");
    if (f) {
        fputs("v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 3 2\n", f);
        fclose(f);
        EXPECT_OK(tp_scene_load_file("harness_bare.obj", &scene));
        if (scene) {
            size = 0;
            EXPECT_OK(tp_scene_notes(scene, NULL, 0, &size));
            CHECK(size > 10 && size < sizeof notes);
            notes[0] = 'x';
            EXPECT_STATUS(tp_scene_notes(scene, notes, 4, &size), TP_ERROR_BUFFER_TOO_SMALL);
            CHECK(notes[0] == '\0');
            EXPECT_OK(tp_scene_notes(scene, notes, sizeof notes, NULL));
            CHECK(strlen(notes) + 1 == size && strstr(notes, "harness_bare.obj") != NULL && strstr(notes, "default") != NULL);
            CHECK(notes[strlen(notes) - 1] == '\n');
            EXPECT_STATUS(tp_scene_notes(NULL, notes, sizeof notes, &size), TP_ERROR_INVALID_ARGUMENT);
            tp_scene_release(scene);
            scene = NULL;
        }
        remove("harness_bare.obj");
    }
    /* A file the OBJ refers to that is missing: TP_ERROR_SCENE naming both, no scene. */
    f = fopen("harness_missing_mtl.obj", "w");
    if (f) {
        fputs("mtllib harness_nowhere.mtl\nv 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 3 2\n", f);
        fclose(f);
        EXPECT_STATUS(tp_scene_load_file("harness_missing_mtl.obj", &scene), TP_ERROR_SCENE);
        CHECK(strstr(tp_last_error(), "harness_missing_mtl.obj") != NULL && strstr(tp_last_error(), "harness_nowhere.mtl") != NULL);
        CHECK(scene == NULL);
        remove("harness_missing_mtl.obj");
    }
    /* A truncated .glb and a light of an unknown type. */
    f = fopen("harness_truncated.glb", "wb");
    if (f) {
        fwrite("glTF\x02\x00\x00\x00\x00\x10\x00\x00", 1, 12, f); /* declares 4096 bytes, holds 12 */
        fclose(f);
        EXPECT_STATUS(tp_scene_load_file("harness_truncated.glb", &scene), TP_ERROR_SCENE);
        CHECK(strstr(tp_last_error(), "truncated") != NULL);
        remove("harness_truncated.glb");
    }
    f = fopen("harness_laser.gltf", "w");
    if (f) {
        fputs("{\"asset\": {\"version\": \"2.0\"}, \"extensions\": {\"KHR_lights_punctual\": {\"lights\": "
              "[{\"type\": \"laser\", \"intensity\": 1}]}}}", f);
        fclose(f);
        EXPECT_STATUS(tp_scene_load_file("harness_laser.gltf", &scene), TP_ERROR_SCENE);
        CHECK(strstr(tp_last_error(), "laser") != NULL);
        remove("harness_laser.gltf");
    }
    CHECK(scene == NULL);
}
