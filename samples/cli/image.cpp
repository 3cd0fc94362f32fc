// Pictures for the demo: a colour ramp over scalar values and PNG output through stb_image_write.
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

#include "cli.h"

#include <algorithm>
#include <cmath>

namespace cli {

namespace {

// Control points of the heat ramp: dark blue, purple, red, orange, yellow, near white.
const float kHeat[6][3] = {{0.02f, 0.02f, 0.15f}, {0.35f, 0.05f, 0.45f}, {0.75f, 0.15f, 0.25f},
                           {0.95f, 0.45f, 0.05f}, {0.98f, 0.80f, 0.15f}, {1.00f, 1.00f, 0.85f}};
// Of the diverging ramp: dark blue, light blue, white (the middle: no difference), light red, dark red.
const float kDiverging[5][3] = {{0.02f, 0.19f, 0.38f}, {0.57f, 0.77f, 0.87f}, {0.97f, 0.97f, 0.97f},
                                {0.96f, 0.65f, 0.51f}, {0.40f, 0.00f, 0.12f}};

void append_bytes(void* context, void* data, int size) {
    auto* out = static_cast<std::vector<unsigned char>*>(context);
    const auto* bytes = static_cast<const unsigned char*>(data);
    out->insert(out->end(), bytes, bytes + size);
}

}  // namespace

Image colour_map(const std::vector<float>& values, int width, int height, float lo, float hi, Ramp ramp) {
    const float(*points)[3] = ramp == Ramp::heat ? kHeat : kDiverging;
    const int segments = ramp == Ramp::heat ? 5 : 4;
    Image image;
    image.width = width;
    image.height = height;
    image.rgb.resize(size_t(width) * height * 3);
    const float span = hi > lo ? hi - lo : 1.0f;
    for (size_t i = 0; i < size_t(width) * height; ++i) {
        float t = std::isfinite(values[i]) ? (values[i] - lo) / span : 0.0f;
        t = std::min(std::max(t, 0.0f), 1.0f) * float(segments);
        const int k = std::min(int(t), segments - 1);
        const float f = t - float(k);
        for (int c = 0; c < 3; ++c) {
            const float v = points[k][c] + f * (points[k + 1][c] - points[k][c]);
            image.rgb[3 * i + c] = static_cast<unsigned char>(std::lround(v * 255.0f));
        }
    }
    return image;
}

void mark(Image& image, int x, int y, const unsigned char colour[3], int radius) {
    for (int dy = -radius; dy <= radius; ++dy)
        for (int dx = -radius; dx <= radius; ++dx) {
            const int px = x + dx, py = y + dy;
            if (dx * dx + dy * dy > radius * radius || px < 0 || py < 0 || px >= image.width || py >= image.height)
                continue;
            std::copy(colour, colour + 3, &image.rgb[3 * (size_t(py) * image.width + px)]);
        }
}

void write_png(const std::string& path, const Image& image) {
    std::vector<unsigned char> png;
    if (!stbi_write_png_to_func(append_bytes, &png, image.width, image.height, 3, image.rgb.data(), image.width * 3))
        throw Failure("cannot encode " + path + " as PNG");
    write_file_atomically(path, png.data(), png.size());
}

}  // namespace cli
