/*
 * A program outside the repository's build: it sees only the installed header and library. Loads the
 * golden store (argv[1]), checks the library's version against the header's and that the centroid of
 * its tetrahedron blends the four probes equally; argv[2] ("full" or "runtime") says whether building a
 * store must work or be refused as unsupported.
 */
#include <tetprobe/tetprobe.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

int main(int argc, char** argv) {
    tp_store* store = NULL;
    tp_store* built = NULL;
    const float centroid[3] = {10.25f, -19.75f, 30.75f};
    static const uint32_t inputs[4] = {0, 1, 2, 4};
    const float corners[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    float out[27], mean[27], probe[27];
    int k, i, full;
    tp_status build_status;
    if (argc < 3) return 2;
    full = strcmp(argv[2], "full") == 0;
    if (tp_version() != TP_VERSION) {
        printf("version %x, header %x\n", (unsigned)tp_version(), (unsigned)TP_VERSION);
        return 1;
    }
    if (tp_store_load_file(argv[1], &store) != TP_OK) {
        printf("load: %s\n", tp_last_error());
        return 1;
    }
    memset(mean, 0, sizeof mean);
    for (i = 0; i < 4; ++i) {
        if (tp_store_probe_sh(store, inputs[i], probe) != TP_OK) return 1;
        for (k = 0; k < 27; ++k) mean[k] += 0.25f * probe[k];
    }
    if (tp_store_interpolate(store, centroid, NULL, out) != TP_OK) return 1;
    for (k = 0; k < 27; ++k)
        if (fabs(out[k] - mean[k]) > 1e-6) {
            printf("sh[%d] = %g, expected %g\n", k, out[k], mean[k]);
            return 1;
        }
    tp_store_release(store);
    build_status = tp_store_build(corners, 0, NULL, 0, 4, NULL, &built);
    tp_store_release(built);
    if (build_status != (full ? TP_OK : TP_ERROR_UNSUPPORTED)) {
        printf("tp_store_build: %s (%s)\n", tp_status_name(build_status), tp_last_error());
        return 1;
    }
    printf("consumer ok (%s)\n", argv[2]);
    return 0;
}
