/* Shadow caster volumes and the AABB and sphere tests against them. */
#include "harness.h"

static const float kCubePlanes[24] = {1, 0, 0, 1, -1, 0, 0, 1, 0, 1, 0, 1, 0, -1, 0, 1, 0, 0, 1, 1, 0, 0, -1, 1};

static int inside_all(const float* planes, size_t count, const float p[3], float slack) {
    size_t i;
    for (i = 0; i < count; ++i) {
        const float* q = planes + 4 * i;
        float n = sqrtf(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
        if (q[0] * p[0] + q[1] * p[1] + q[2] * p[2] + q[3] < -slack * n) return 0;
    }
    return 1;
}

static int sphere_hits(const float* planes, size_t count, float x, float y, float z, float r) {
    float c[3];
    int hit = -1;
    c[0] = x, c[1] = y, c[2] = z;
    EXPECT_OK(tp_volume_test_sphere(planes, count, c, r, &hit));
    return hit;
}

static int box_hits(const float* planes, size_t count, float x, float y, float z, float half) {
    float lo[3], hi[3];
    int hit = -1;
    lo[0] = x - half, lo[1] = y - half, lo[2] = z - half;
    hi[0] = x + half, hi[1] = y + half, hi[2] = z + half;
    EXPECT_OK(tp_volume_test_aabb(planes, count, lo, hi, &hit));
    return hit;
}

void test_shadow_caster_volumes(void) {
    size_t bound = tp_shadow_caster_volume_bound(6), count = 0;
    float* planes;
    const float light_position[3] = {0.0f, 5.0f, 0.0f};
    const float down[3] = {0.0f, -1.0f, 0.0f};
    int corner, contained = 1;
    CHECK(bound >= 6);
    CHECK(tp_shadow_caster_volume_bound(12) >= bound);
    planes = (float*)malloc(4 * bound * sizeof(float));
    if (!planes) return;

    /* Point light above the cube [-1, 1]^3: the volume is the hull of the cube and the light. */
    EXPECT_OK(tp_shadow_caster_volume(kCubePlanes, 6, TP_LIGHT_POINT, light_position, planes, bound, &count));
    CHECK(count >= 5 && count <= bound);
    for (corner = 0; corner < 8; ++corner) {
        float p[3];
        p[0] = (corner & 1) ? 1.0f : -1.0f;
        p[1] = (corner & 2) ? 1.0f : -1.0f;
        p[2] = (corner & 4) ? 1.0f : -1.0f;
        contained &= inside_all(planes, count, p, 1e-4f);
    }
    contained &= inside_all(planes, count, light_position, 1e-4f);
    CHECK(contained);
    CHECK(sphere_hits(planes, count, 0.0f, 3.0f, 0.0f, 0.1f) == 1);  /* between light and cube */
    CHECK(sphere_hits(planes, count, 0.0f, 0.0f, 0.0f, 0.1f) == 1);  /* inside the cube */
    CHECK(sphere_hits(planes, count, 3.0f, 3.0f, 0.0f, 0.5f) == 0);  /* beside the cone */
    CHECK(sphere_hits(planes, count, 0.0f, 7.0f, 0.0f, 0.5f) == 0);  /* behind the light */
    CHECK(sphere_hits(planes, count, 0.0f, -3.0f, 0.0f, 0.5f) == 0); /* below the cube */
    CHECK(box_hits(planes, count, 0.2f, 2.0f, -0.2f, 0.2f) == 1);
    CHECK(box_hits(planes, count, 4.0f, 0.0f, 4.0f, 0.5f) == 0);
    CHECK(box_hits(planes, count, 0.0f, 8.0f, 0.0f, 0.5f) == 0);
    CHECK(box_hits(planes, count, 0.0f, 5.0f, 0.0f, 10.0f) == 1);    /* a box containing everything */

    /* Directional light travelling down: the cube swept up to infinity. */
    EXPECT_OK(tp_shadow_caster_volume(kCubePlanes, 6, TP_LIGHT_DIRECTIONAL, down, planes, bound, &count));
    CHECK(count >= 5 && count <= bound);
    CHECK(sphere_hits(planes, count, 0.0f, 1000.0f, 0.0f, 0.5f) == 1);
    CHECK(sphere_hits(planes, count, 0.5f, 3.0f, -0.5f, 0.1f) == 1);
    CHECK(sphere_hits(planes, count, 5.0f, 3.0f, 0.0f, 0.5f) == 0);
    CHECK(sphere_hits(planes, count, 0.0f, -5.0f, 0.0f, 1.0f) == 0);
    CHECK(box_hits(planes, count, 0.0f, 50.0f, 0.0f, 2.0f) == 1);
    CHECK(box_hits(planes, count, 0.0f, 50.0f, 10.0f, 2.0f) == 0);

    /* Errors. */
    {
        float nan_light[3];
        const float lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
        int hit;
        nan_light[0] = (float)NAN, nan_light[1] = 0.0f, nan_light[2] = 0.0f;
        EXPECT_STATUS(tp_shadow_caster_volume(kCubePlanes, 6, TP_LIGHT_POINT, light_position, planes, 2, &count),
                      TP_ERROR_BUFFER_TOO_SMALL);
        EXPECT_STATUS(tp_shadow_caster_volume(NULL, 6, TP_LIGHT_POINT, light_position, planes, bound, &count),
                      TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_shadow_caster_volume(kCubePlanes, 6, TP_LIGHT_POINT, NULL, planes, bound, &count),
                      TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_shadow_caster_volume(kCubePlanes, 6, TP_LIGHT_POINT, light_position, NULL, bound, &count),
                      TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_shadow_caster_volume(kCubePlanes, 6, TP_LIGHT_POINT, light_position, planes, bound, NULL),
                      TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_shadow_caster_volume(kCubePlanes, 6, 77u, light_position, planes, bound, &count),
                      TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_shadow_caster_volume(kCubePlanes, 6, TP_LIGHT_POINT, nan_light, planes, bound, &count),
                      TP_ERROR_INVALID_ARGUMENT);
        EXPECT_FAILS(tp_shadow_caster_volume(kCubePlanes, 0, TP_LIGHT_POINT, light_position, planes, bound, &count));
        EXPECT_STATUS(tp_volume_test_aabb(NULL, 6, lo, hi, &hit), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_volume_test_aabb(kCubePlanes, 6, NULL, hi, &hit), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_volume_test_aabb(kCubePlanes, 6, lo, hi, NULL), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_volume_test_aabb(kCubePlanes, 6, lo, nan_light, &hit), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_volume_test_sphere(NULL, 6, lo, 1.0f, &hit), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_volume_test_sphere(kCubePlanes, 6, lo, -1.0f, &hit), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_volume_test_sphere(kCubePlanes, 6, lo, (float)NAN, &hit), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_volume_test_sphere(kCubePlanes, 6, lo, 1.0f, NULL), TP_ERROR_INVALID_ARGUMENT);
    }
    free(planes);
}
