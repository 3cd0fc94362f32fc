// `tetprobe demo`: (a) a built-in probe cloud over an analytic lighting field — build, follow a
// moving object with a hint, measure the error, picture a slice; (b) when the sample scene
// two_rooms.json is found, place its probes automatically, bake them, build the store and picture a
// slice of the baked light.
#include "cli.h"

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>
#include <unistd.h>

namespace cli {

namespace {

namespace fs = std::filesystem;

// ---- (a) the analytic field: an ambient term and a sun, both linear in position (a tetrahedral
// interpolation reproduces them up to half precision), plus a lamp whose direction and 1/(r^2+d^2)
// falloff (r = 1.5, about the probe spacing) vary smoothly but not linearly.

constexpr float kLamp[3] = {7.0f, 2.5f, 3.0f};

void field(const float p[3], bool with_lamp, float out[TP_SH_FLOATS]) {
    std::fill(out, out + TP_SH_FLOATS, 0.0f);
    const float ambient[3] = {0.20f + 0.03f * p[0], 0.22f + 0.02f * p[1], 0.30f - 0.02f * p[2]};
    tp_sh_add_ambient(out, ambient);
    const float sun_direction[3] = {0.4f, -0.8f, 0.3f};
    const float sun_scale = 0.5f + 0.05f * p[0];
    const float sun[3] = {1.0f * sun_scale, 0.9f * sun_scale, 0.7f * sun_scale};
    tp_sh_add_directional(out, sun_direction, sun);
    if (!with_lamp) return;
    float d[3] = {p[0] - kLamp[0], p[1] - kLamp[1], p[2] - kLamp[2]};
    const float d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    const float length = std::sqrt(d2);
    if (length < 1e-6f) return;
    for (float& v : d) v /= length;
    const float falloff = 3.0f / (2.25f + d2);
    const float lamp[3] = {1.0f * falloff, 0.6f * falloff, 0.3f * falloff};
    tp_sh_add_directional(out, d, lamp);
}

float luminance(const float rgb[3]) { return 0.2126f * rgb[0] + 0.7152f * rgb[1] + 0.0722f * rgb[2]; }

float irradiance_up(const float sh[TP_SH_FLOATS]) {
    const float up[3] = {0, 1, 0};
    float rgb[3];
    check(tp_sh_eval_irradiance(sh, up, rgb), "tp_sh_eval_irradiance");
    return luminance(rgb);
}

// Average irradiance over all normals: pi * L00 * Y00 per channel.
float mean_irradiance(const float sh[TP_SH_FLOATS]) {
    const float rgb[3] = {3.14159265f * 0.282095f * sh[0], 3.14159265f * 0.282095f * sh[9],
                          3.14159265f * 0.282095f * sh[18]};
    return luminance(rgb);
}

// A jittered 8 x 3 x 8 lattice over [0, 10] x [0, 4] x [0, 10] and extra probes around the lamp.
std::vector<float> probe_cloud() {
    std::mt19937 rng(1234);
    std::uniform_real_distribution<float> jitter(-0.25f, 0.25f), unit(-1.0f, 1.0f);
    std::vector<float> positions;
    const int nx = 8, ny = 3, nz = 8;
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                const float sx = 10.0f / (nx - 1), sy = 4.0f / (ny - 1), sz = 10.0f / (nz - 1);
                positions.push_back(i * sx + jitter(rng) * sx);
                positions.push_back(j * sy + jitter(rng) * sy * 0.5f);
                positions.push_back(k * sz + jitter(rng) * sz);
            }
    for (int n = 0; n < 48; ++n) {
        positions.push_back(kLamp[0] + 1.5f * unit(rng));
        positions.push_back(std::min(std::max(kLamp[1] + 1.2f * unit(rng), 0.0f), 4.0f));
        positions.push_back(kLamp[2] + 1.5f * unit(rng));
    }
    return positions;
}

tp_location locate(const tp_store* store, const float p[3], int32_t* hint) {
    tp_location location;
    std::memset(&location, 0, sizeof location);
    location.struct_size = sizeof location;
    check(tp_store_locate(store, p, hint, &location), "tp_store_locate");
    return location;
}

// A horizontal slice y = height over [x0, x1] x [z0, z1]: one value per pixel from `value`.
template <class Value>
std::vector<float> slice(int width, int height, const float box[4], float y, Value value) {
    std::vector<float> values(size_t(width) * height);
    for (int row = 0; row < height; ++row)
        for (int column = 0; column < width; ++column) {
            const float p[3] = {box[0] + (box[1] - box[0]) * (column + 0.5f) / width, y,
                                box[2] + (box[3] - box[2]) * (row + 0.5f) / height};
            values[size_t(row) * width + column] = value(p);
        }
    return values;
}

void mark_probes(Image& image, int x_offset, int width, int height, const float box[4], float y, float band,
                 const std::vector<float>& positions, bool dark = false) {
    const unsigned char white[3] = {255, 255, 255}, black[3] = {0, 0, 0};
    for (size_t i = 0; i < positions.size() / 3; ++i) {
        const float* p = &positions[3 * i];
        if (std::fabs(p[1] - y) > band) continue;
        const int column = int((p[0] - box[0]) / (box[1] - box[0]) * width);
        const int row = int((p[2] - box[2]) / (box[3] - box[2]) * height);
        if (column >= 0 && column < width && row >= 0 && row < height)
            mark(image, x_offset + column, row, dark ? black : white, dark ? 1 : 2);
    }
}

// Which pixels of a slice (as `slice` samples them) lie inside the scene's geometry (tp_find_inside_probes:
// a wall's thickness, a closed mesh), 1 per pixel; tested at every other pixel and column, the 2 x 2 block
// taking its answer (the test casts 64 rays a point).
std::vector<unsigned char> solid_pixels(const tp_scene* scene, int width, int height, const float box[4], float y) {
    std::vector<float> points;
    const int columns = (width + 1) / 2, rows = (height + 1) / 2;
    for (int row = 0; row < rows; ++row)
        for (int column = 0; column < columns; ++column) {
            points.push_back(box[0] + (box[1] - box[0]) * float(2 * column + 1) / float(width));
            points.push_back(y);
            points.push_back(box[2] + (box[3] - box[2]) * float(2 * row + 1) / float(height));
        }
    const size_t count = points.size() / 3;
    std::vector<uint32_t> inside(count);
    size_t found = 0;
    check(tp_find_inside_probes(scene, points.data(), 0, count, inside.data(), inside.size(), &found),
          "finding the geometry in the slice");
    std::vector<unsigned char> solid(size_t(width) * height, 0);
    for (size_t k = 0; k < found; ++k) {
        const int column = int(inside[k] % columns), row = int(inside[k] / columns);
        for (int dy = 0; dy < 2; ++dy)
            for (int dx = 0; dx < 2; ++dx)
                if (2 * row + dy < height && 2 * column + dx < width)
                    solid[size_t(2 * row + dy) * width + 2 * column + dx] = 1;
    }
    return solid;
}

void paint_solid(Image& image, const std::vector<unsigned char>& solid) {
    const unsigned char grey[3] = {150, 150, 150};
    for (size_t i = 0; i < solid.size(); ++i)
        if (solid[i]) std::copy(grey, grey + 3, &image.rgb[3 * i]);
}

void print_row(const char* name, const std::string& value) { std::printf("| %-38s | %22s |\n", name, value.c_str()); }

std::string format(const char* pattern, double value) {
    char text[64];
    std::snprintf(text, sizeof text, pattern, value);
    return text;
}

void demo_analytic_field(const fs::path& out_dir) {
    std::printf("## (a) analytic lighting field\n\n");
    const std::vector<float> positions = probe_cloud();
    const size_t count = positions.size() / 3;
    std::vector<float> sh(count * TP_SH_FLOATS), linear_sh(count * TP_SH_FLOATS);
    for (size_t i = 0; i < count; ++i) {
        field(&positions[3 * i], true, &sh[TP_SH_FLOATS * i]);
        field(&positions[3 * i], false, &linear_sh[TP_SH_FLOATS * i]);
    }
    StorePtr store = build_store(positions, sh, false);
    StorePtr linear_store = build_store(positions, linear_sh, false);
    const tp_store_info info = store_info(store.get());

    // An object moving through the volume, its hint kept from frame to frame.
    const int frames = 3000;
    int32_t hint = -1;
    double coherent_steps = 0, cold_steps = 0, max_error = 0, max_linear_error = 0, field_range = 0, sum_error = 0;
    int inside_frames = 0;
    std::printf("| frame | position | cell | kind | steps | irradiance (+y) | analytic |\n");
    std::printf("| ---: | --- | ---: | --- | ---: | ---: | ---: |\n");
    for (int frame = 0; frame < frames; ++frame) {
        const double t = 6.283185307 * 3.0 * frame / frames;
        const float p[3] = {float(5.0 + 4.6 * std::sin(t)), float(1.8 + 1.5 * std::sin(2.3 * t)),
                            float(5.0 + 4.6 * std::sin(1.7 * t + 0.5))};
        const tp_location moving = locate(store.get(), p, &hint);
        if (frame > 0) coherent_steps += moving.steps;
        cold_steps += locate(store.get(), p, nullptr).steps;
        float interpolated[TP_SH_FLOATS], exact[TP_SH_FLOATS], linear[TP_SH_FLOATS], exact_linear[TP_SH_FLOATS];
        int32_t same_cell = moving.cell;
        check(tp_store_interpolate(store.get(), p, &same_cell, interpolated), "tp_store_interpolate");
        field(p, true, exact);
        if (moving.cell_kind == TP_CELL_INNER) {
            ++inside_frames;
            check(tp_store_interpolate(linear_store.get(), p, nullptr, linear), "tp_store_interpolate");
            field(p, false, exact_linear);
            for (int k = 0; k < TP_SH_FLOATS; ++k) {
                max_error = std::max(max_error, double(std::fabs(interpolated[k] - exact[k])));
                sum_error += std::fabs(interpolated[k] - exact[k]) / TP_SH_FLOATS;
                max_linear_error = std::max(max_linear_error, double(std::fabs(linear[k] - exact_linear[k])));
                field_range = std::max(field_range, double(std::fabs(exact[k])));
            }
        }
        if (frame % 600 == 0)
            std::printf("| %d | (%.2f, %.2f, %.2f) | %d | %s | %u | %.4f | %.4f |\n", frame, p[0], p[1], p[2],
                        moving.cell, moving.cell_kind == TP_CELL_OUTER ? "outer" : "inner", moving.steps,
                        irradiance_up(interpolated), irradiance_up(exact));
    }

    std::printf("\n| %-38s | %22s |\n| %.38s | %.22s |\n", "store", "value", "--------------------------------------",
                "---------------------:");
    print_row("probes", std::to_string(info.probes));
    print_row("cells (inner + outer)", std::to_string(info.cells) + " (" + std::to_string(info.inner_cells) + " + " +
                                           std::to_string(info.outer_cells) + ")");
    print_row("bytes", std::to_string(info.bytes) + " (" + format("%.1f", double(info.bytes) / info.probes) + "/probe)");
    print_row("index width", std::to_string(info.index_bits) + " bits");
    print_row("frames (inside the hull)", std::to_string(frames) + " (" + std::to_string(inside_frames) + ")");
    print_row("mean steps per query, with hint", format("%.3f", coherent_steps / (frames - 1)));
    print_row("mean steps per query, no hint", format("%.3f", cold_steps / frames));
    print_row("mean SH error inside hull, full", format("%.5f", sum_error / std::max(inside_frames, 1)));
    print_row("max SH error inside hull, full", format("%.5f", max_error) + format(" (%.1f%% of max)", 100 * max_error / field_range));
    print_row("max SH error inside hull, linear part", format("%.6f", max_linear_error));
    std::printf("\n(error: |interpolated - analytic| over the 27 coefficients; the linear part (ambient + sun) is "
                "reproduced up to half precision, the lamp's 1/(r^2+d^2) term is not)\n");

    // Picture: slice y = 1.5 over [-2, 12]^2 (outer cells beyond the probes), analytic | interpolated.
    const int size = 360;
    const float box[4] = {-2.0f, 12.0f, -2.0f, 12.0f}, y = 1.5f;
    const std::vector<float> analytic = slice(size, size, box, y, [](const float p[3]) {
        float s[TP_SH_FLOATS];
        field(p, true, s);
        return irradiance_up(s);
    });
    int32_t scan_hint = -1;
    const std::vector<float> interpolated = slice(size, size, box, y, [&](const float p[3]) {
        float s[TP_SH_FLOATS];
        check(tp_store_interpolate(store.get(), p, &scan_hint, s), "tp_store_interpolate");
        return irradiance_up(s);
    });
    // One colour scale, the analytic field's range, for both panels.
    float lo = 1e30f, hi = -1e30f;
    for (float v : analytic) lo = std::min(lo, v), hi = std::max(hi, v);
    Image right = colour_map(interpolated, size, size, lo, hi);
    mark_probes(right, 0, size, size, box, y, 0.4f, positions);
    const Image image = framed_figure({colour_map(analytic, size, size, lo, hi), right}, {"analytic", "interpolated"},
                                      {box[0], box[1], box[2], box[3]}, lo, hi, "irradiance");
    const fs::path png = out_dir / "analytic_irradiance.png", blob = out_dir / "analytic.tpb";
    write_png(png.string(), image);
    check(tp_store_save_file(store.get(), blob.string().c_str()), "saving the store");
    std::printf("\nwrote %s (irradiance on +y at y = %.1f: analytic | interpolated, probes within 0.4 dotted)\n",
                png.string().c_str(), y);
    std::printf("wrote %s\n\n", blob.string().c_str());
}

// ---- (b) the sample scene two_rooms.json, baked.

fs::path find_scene(const Arguments& a) {
    if (a.has("--scene")) {
        const fs::path explicit_path = a.value("--scene", "");
        if (!fs::exists(explicit_path)) throw Failure("scene " + explicit_path.string() + " does not exist");
        return explicit_path;
    }
    std::vector<fs::path> candidates;
    // The source tree this file was compiled from, then relative to the executable, then the working directory.
    candidates.push_back(fs::path(__FILE__).parent_path().parent_path() / "scenes" / "two_rooms.json");
    char exe[4096];
    const ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n > 0) {
        exe[n] = '\0';
        const fs::path dir = fs::path(exe).parent_path();
        candidates.push_back(dir / ".." / ".." / "samples" / "scenes" / "two_rooms.json");
        candidates.push_back(dir / ".." / "samples" / "scenes" / "two_rooms.json");
    }
    candidates.push_back(fs::path("samples") / "scenes" / "two_rooms.json");
    for (const fs::path& candidate : candidates) {
        std::error_code error;
        if (fs::exists(candidate, error)) return candidate;
    }
    return {};
}

void demo_baked_scene(const fs::path& scene_path, const Arguments& a, const fs::path& out_dir) {
    std::printf("## (b) baked scene %s\n\n", scene_path.string().c_str());
    tp_scene* raw = nullptr;
    check(tp_scene_load_file(scene_path.string().c_str(), &raw), "loading the scene");
    ScenePtr scene(raw);
    place_scene_probes(scene.get(), 0.5f, 0.15f);
    const BakeSettings settings = bake_settings(a, 128);
    const BakeResult baked = bake_scene(scene.get(), settings);
    const size_t count = baked.positions.size() / 3;
    StorePtr store = build_store(baked.positions, baked.sh, false);
    const tp_store_info info = store_info(store.get());

    std::printf("\n| %-38s | %22s |\n| %.38s | %.22s |\n", "bake", "value", "--------------------------------------",
                "---------------------:");
    print_row("probes", std::to_string(count));
    print_row("rays per probe", std::to_string(settings.rays));
    print_row("bounces (asked / simulated)",
              std::to_string(settings.bounces) + " / " + std::to_string(baked.plan.bounces));
    print_row("direct lights / realtime lights",
              std::to_string(baked.plan.direct_lights) + " / " + std::to_string(baked.plan.realtime_lights));
    print_row("shadow casters kept / considered", std::to_string(baked.plan.shadow_casters) + " / " +
                                                      std::to_string(baked.plan.shadow_caster_candidates));
    print_row("bake time", format("%.2f s", baked.seconds));
    print_row("probe-rays per second", format("%.0f", double(count) * settings.rays / std::max(baked.seconds, 1e-9)));
    print_row("store cells (inner + outer)", std::to_string(info.cells) + " (" + std::to_string(info.inner_cells) +
                                                 " + " + std::to_string(info.outer_cells) + ")");
    print_row("store bytes", std::to_string(info.bytes));

    // Slice through the probes' median height, over their x-z extent with a margin, aspect kept.
    std::vector<float> heights;
    float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
    for (size_t i = 0; i < count; ++i) {
        heights.push_back(baked.positions[3 * i + 1]);
        for (int k = 0; k < 3; ++k)
            lo[k] = std::min(lo[k], baked.positions[3 * i + k]), hi[k] = std::max(hi[k], baked.positions[3 * i + k]);
    }
    std::nth_element(heights.begin(), heights.begin() + heights.size() / 2, heights.end());
    const float y = heights[heights.size() / 2];
    const float margin = 0.05f * std::max(hi[0] - lo[0], hi[2] - lo[2]) + 1e-3f;
    const float box[4] = {lo[0] - margin, hi[0] + margin, lo[2] - margin, hi[2] + margin};
    const float aspect = (box[3] - box[2]) / (box[1] - box[0]);
    const int width = aspect <= 1 ? 480 : std::max(16, int(480 / aspect));
    const int height = aspect <= 1 ? std::max(16, int(480 * aspect)) : 480;
    int32_t scan_hint = -1;
    const std::vector<float> values = slice(width, height, box, y, [&](const float p[3]) {
        float s[TP_SH_FLOATS];
        check(tp_store_interpolate(store.get(), p, &scan_hint, s), "tp_store_interpolate");
        return mean_irradiance(s);
    });
    float vmax = 0;
    for (float v : values) vmax = std::max(vmax, v);
    Image slice_image = colour_map(values, width, height, 0.0f, vmax);
    mark_probes(slice_image, 0, width, height, box, y, 0.25f * (hi[1] - lo[1]) + 1e-3f, baked.positions);
    const Image image = framed_figure({slice_image}, {"y = " + format("%.2f", y)}, {box[0], box[1], box[2], box[3]},
                                      0.0f, vmax, "irradiance");
    const std::string stem = scene_path.stem().string();
    const fs::path png = out_dir / (stem + "_irradiance.png"), blob = out_dir / (stem + ".tpb");
    write_png(png.string(), image);
    check(tp_store_save_file(store.get(), blob.string().c_str()), "saving the store");
    std::printf("\nwrote %s (mean irradiance over directions at y = %.2f, x right, z down, probes dotted)\n",
                png.string().c_str(), y);
    std::printf("wrote %s\n", blob.string().c_str());

    // Leak control: the same slice from a store built with the scene (probe pairs that cannot see each
    // other are stored), beside the plain one and their difference, with the scene's solid geometry (the
    // wall) in grey: light no longer bleeds through the wall.
    tp_build_options with_scene;
    check(tp_build_options_init(&with_scene), "tp_build_options_init");
    with_scene.scene = scene.get();
    tp_store* raw_leak = nullptr;
    check(tp_store_build(baked.positions.data(), 0, baked.sh.data(), 0, count, &with_scene, &raw_leak), "build");
    StorePtr leak(raw_leak);
    const std::vector<float> fixed = slice(width, height, box, y, [&](const float p[3]) {
        float s[TP_SH_FLOATS];
        check(tp_store_interpolate(leak.get(), p, &scan_hint, s), "tp_store_interpolate");
        return mean_irradiance(s);
    });
    std::vector<float> difference(values.size());
    float largest = 0;
    size_t largest_at = 0;
    for (size_t i = 0; i < values.size(); ++i) {
        difference[i] = values[i] - fixed[i];
        if (std::fabs(difference[i]) > largest) largest = std::fabs(difference[i]), largest_at = i;
    }
    const float span = largest > 0 ? largest : 1.0f;
    const std::vector<unsigned char> solid = solid_pixels(scene.get(), width, height, box, y);
    Image right = colour_map(fixed, width, height, 0.0f, vmax);
    mark_probes(right, 0, width, height, box, y, 0.25f * (hi[1] - lo[1]) + 1e-3f, baked.positions);
    Image change = colour_map(difference, width, height, -span, span, Ramp::diverging);
    mark_probes(change, 0, width, height, box, y, 0.25f * (hi[1] - lo[1]) + 1e-3f, baked.positions, true);
    Image left = slice_image;
    for (Image* panel : {&left, &right, &change}) paint_solid(*panel, solid);
    const Image figure = framed_figure({left, right, change},
                                       {"without leak control", "with leak control", "without - with"},
                                       {box[0], box[1], box[2], box[3]},
                                       {ColourBar{1, 0.0f, vmax, "irradiance"},
                                        ColourBar{2, -span, span, "difference", Ramp::diverging}},
                                       "grey = inside geometry (the wall)   dots = probes near the slice");
    const fs::path leak_png = out_dir / (stem + "_leak_fix.png");
    write_png(leak_png.string(), figure);
    const float at_x = box[0] + (box[1] - box[0]) * (float(largest_at % width) + 0.5f) / float(width);
    const float at_z = box[2] + (box[3] - box[2]) * (float(largest_at / width) + 0.5f) / float(height);
    std::printf("wrote %s (the same slice without | with leak control | their difference: %u probe pairs cannot see "
                "each other; the largest change, %.3f of irradiance %.3f, at x = %.2f, z = %.2f)\n",
                leak_png.string().c_str(), store_info(leak.get()).leak_edges, difference[largest_at], values[largest_at],
                at_x, at_z);
}

}  // namespace

int command_demo(const std::vector<std::string>& args) {
    const Arguments a = parse_arguments(args, {"--out", "--scene", "--rays", "--bounces", "--seed", "--threads"}, {});
    if (!a.positional.empty()) throw UsageError("demo takes no positional arguments");
    const fs::path out_dir = a.value("--out", "tetprobe-demo");
    std::error_code error;
    fs::create_directories(out_dir, error);
    if (error) throw Failure("cannot create " + out_dir.string() + ": " + error.message());
    const uint32_t v = tp_version();
    std::printf("# tetprobe %u.%u.%u demo\n\n", v >> 16, (v >> 8) & 0xFFu, v & 0xFFu);
    demo_analytic_field(out_dir);
    const fs::path scene = find_scene(a);
    if (scene.empty()) {
        std::printf("## (b) skipped: samples/scenes/two_rooms.json not found (pass --scene FILE)\n");
        return 0;
    }
    demo_baked_scene(scene, a, out_dir);
    return 0;
}

}  // namespace cli
