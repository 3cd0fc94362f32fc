/* Version, status names, the thread-local message, option struct defaults. */
#include "harness.h"

void test_version_and_status_names(void) {
    static const char* const names[] = {
        "TP_OK", "TP_ERROR_INVALID_ARGUMENT", "TP_ERROR_OUT_OF_MEMORY", "TP_ERROR_IO", "TP_ERROR_INVALID_BLOB",
        "TP_ERROR_VERSION", "TP_ERROR_DEGENERATE", "TP_ERROR_TETGEN", "TP_ERROR_CANCELLED", "TP_ERROR_OUTSIDE",
        "TP_ERROR_SCENE", "TP_ERROR_UNSUPPORTED", "TP_ERROR_BUFFER_TOO_SMALL", "TP_ERROR_INTERNAL"};
    int i;
    uint32_t version = tp_version();
    CHECK(version == TP_VERSION);
    CHECK((version >> 16) == TP_VERSION_MAJOR);
    CHECK(((version >> 8) & 0xFFu) == TP_VERSION_MINOR);
    CHECK((version & 0xFFu) == TP_VERSION_PATCH);
    for (i = 0; i <= (int)TP_ERROR_INTERNAL; ++i) CHECK(strcmp(tp_status_name((tp_status)i), names[i]) == 0);
    CHECK(tp_status_name((tp_status)1234) != NULL);
    CHECK(tp_last_error() != NULL);
}

void test_last_error_is_per_call(void) {
    tp_build_options options;
    EXPECT_STATUS(tp_build_options_init(NULL), TP_ERROR_INVALID_ARGUMENT);
    CHECK(strlen(tp_last_error()) > 0);
    EXPECT_OK(tp_build_options_init(&options));
    CHECK(strcmp(tp_last_error(), "") == 0);
}

void test_option_struct_defaults(void) {
    tp_build_options build;
    tp_batch_options batch;
    tp_bake_options bake;
    tp_material material;
    tp_light light;
    memset(&build, 0xAB, sizeof build);
    memset(&bake, 0xAB, sizeof bake);
    memset(&material, 0xAB, sizeof material);
    memset(&light, 0xAB, sizeof light);
    memset(&batch, 0xAB, sizeof batch);
    EXPECT_OK(tp_batch_options_init(&batch));
    CHECK(sizeof batch == 12);
    CHECK(batch.struct_size == sizeof batch);
    CHECK(batch.flags == 0);
    CHECK(batch.threads == 1);
    EXPECT_STATUS(tp_batch_options_init(NULL), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_OK(tp_build_options_init(&build));
    CHECK(build.struct_size == sizeof build);
    CHECK(build.flags == 0);
    CHECK_NEAR(build.merge_tolerance, 1e-6, 1e-12);
    CHECK_NEAR(build.flat_tolerance, 1e-4, 1e-12);
    CHECK(build.progress == NULL);
    CHECK(build.progress_user == NULL);
    EXPECT_OK(tp_bake_options_init(&bake));
    CHECK(bake.struct_size == sizeof bake);
    CHECK(bake.flags == 0);
    CHECK(bake.rays == 256);
    CHECK(bake.bounces == 2);
    CHECK(bake.seed == 0);
    CHECK(bake.threads == 0);
    CHECK(bake.progress == NULL);
    EXPECT_OK(tp_material_init(&material));
    CHECK(material.struct_size == sizeof material);
    CHECK(material.albedo[0] >= 0.0f && material.albedo[0] <= 1.0f);
    CHECK(material.emission[0] == 0.0f && material.emission[1] == 0.0f && material.emission[2] == 0.0f);
    EXPECT_OK(tp_light_init(&light));
    CHECK(light.struct_size == sizeof light);
    CHECK(light.mode == TP_LIGHT_MODE_BAKED);
    CHECK(light.intensity > 0.0f);
    EXPECT_STATUS(tp_bake_options_init(NULL), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_material_init(NULL), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_light_init(NULL), TP_ERROR_INVALID_ARGUMENT);
}
