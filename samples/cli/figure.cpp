// The frame around the demo's slice pictures: titles, axes with ticks in metres, and a colour bar.
#include "cli.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace cli {

namespace {

constexpr int kScale = 2;                           // font pixels are 2x2
constexpr int kCharHeight = kGlyphHeight * kScale;  // 14 px
constexpr int kTick = 5, kGap = 16, kBarWidth = 18;
const unsigned char kBlack[3] = {0, 0, 0};

// Tick values in [lo, hi]: multiples of a step of 1, 2 or 5 times a power of ten, at most about 6.
std::vector<double> ticks(double lo, double hi, int* decimals) {
    const double range = hi > lo ? hi - lo : 1.0;
    const double power = std::pow(10.0, std::floor(std::log10(range / 5.0)));
    double step = power;
    for (const double m : {1.0, 2.0, 5.0, 10.0})
        if (range / (m * power) <= 6.0) {
            step = m * power;
            break;
        }
    *decimals = std::max(0, -int(std::floor(std::log10(step) + 1e-9)));
    std::vector<double> out;
    for (double v = std::ceil(lo / step - 1e-9) * step; v <= hi + 1e-9 * range; v += step) out.push_back(v);
    return out;
}

std::string tick_label(double v, int decimals) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.*f", decimals, std::fabs(v) < 1e-12 ? 0.0 : v);
    return buffer;
}

void fill(Image& image, int x0, int y0, int x1, int y1, const unsigned char colour[3]) {
    for (int y = std::max(y0, 0); y < std::min(y1, image.height); ++y)
        for (int x = std::max(x0, 0); x < std::min(x1, image.width); ++x)
            std::copy(colour, colour + 3, &image.rgb[3 * (size_t(y) * image.width + x)]);
}

void frame(Image& image, int x0, int y0, int width, int height) {
    fill(image, x0 - 1, y0 - 1, x0 + width + 1, y0, kBlack);
    fill(image, x0 - 1, y0 + height, x0 + width + 1, y0 + height + 1, kBlack);
    fill(image, x0 - 1, y0 - 1, x0, y0 + height + 1, kBlack);
    fill(image, x0 + width, y0 - 1, x0 + width + 1, y0 + height + 1, kBlack);
}

void paste(Image& canvas, const Image& panel, int x0, int y0) {
    for (int y = 0; y < panel.height; ++y)
        std::copy(&panel.rgb[3 * size_t(y) * panel.width], &panel.rgb[3 * (size_t(y) + 1) * panel.width],
                  &canvas.rgb[3 * (size_t(y0 + y) * canvas.width + x0)]);
}

}  // namespace

Image framed_figure(const std::vector<Image>& panels, const std::vector<std::string>& titles, const SliceAxes& axes,
                    const std::vector<ColourBar>& bars, const std::string& caption) {
    const int pw = panels.at(0).width, ph = panels.at(0).height;
    int z_decimals, x_decimals;
    const std::vector<double> z_ticks = ticks(axes.z_lo, axes.z_hi, &z_decimals);
    const std::vector<double> x_ticks = ticks(axes.x_lo, axes.x_hi, &x_decimals);
    int z_label_width = text_width("z (m)", kScale);
    for (double v : z_ticks) z_label_width = std::max(z_label_width, text_width(tick_label(v, z_decimals), kScale));

    // Layout, left to right: the z axis, then each panel followed by the colour bars placed after it.
    struct PlacedBar {
        const ColourBar* bar;
        int x, decimals;
        std::vector<double> ticks;
    };
    const int left = z_label_width + kTick + 8, top = 2 * kCharHeight + 12;
    std::vector<int> panel_x;
    std::vector<PlacedBar> placed;
    int x = left;
    for (size_t i = 0; i < panels.size(); ++i) {
        panel_x.push_back(x);
        x += pw + kGap;
        for (const ColourBar& bar : bars) {
            if (bar.after_panel != i) continue;
            PlacedBar p{&bar, x, 0, {}};
            p.ticks = ticks(bar.lo, bar.hi, &p.decimals);
            int labels = 0;
            for (double v : p.ticks) labels = std::max(labels, text_width(tick_label(v, p.decimals), kScale));
            x += std::max(kBarWidth + kTick + 6 + labels, text_width(bar.label, kScale)) + kGap + 8;
            placed.push_back(std::move(p));
        }
    }
    Image canvas;
    canvas.width = std::max(x, left + text_width(caption, kScale)) + 8;
    canvas.height = top + ph + kTick + 2 * kCharHeight + 16 + (caption.empty() ? 0 : kCharHeight + 8);
    canvas.rgb.assign(size_t(canvas.width) * canvas.height * 3, 255);

    draw_text(canvas, 4, top - kCharHeight - 6, "z (m)", kScale, kBlack);
    for (size_t i = 0; i < panels.size(); ++i) {
        const int x0 = panel_x[i];
        paste(canvas, panels[i], x0, top);
        frame(canvas, x0, top, pw, ph);
        if (i < titles.size())
            draw_text(canvas, x0 + (pw - text_width(titles[i], kScale)) / 2, top - kCharHeight - 6, titles[i],
                      kScale, kBlack);
        for (double v : x_ticks) {
            const int tx = x0 + int(std::lround((v - axes.x_lo) / (axes.x_hi - axes.x_lo) * (pw - 1)));
            fill(canvas, tx, top + ph, tx + 1, top + ph + kTick, kBlack);
            const std::string label = tick_label(v, x_decimals);
            draw_text(canvas, tx - text_width(label, kScale) / 2, top + ph + kTick + 3, label, kScale, kBlack);
        }
        draw_text(canvas, x0 + (pw - text_width("x (m)", kScale)) / 2, top + ph + kTick + kCharHeight + 8, "x (m)",
                  kScale, kBlack);
    }
    for (double v : z_ticks) {
        const int y = top + int(std::lround((v - axes.z_lo) / (axes.z_hi - axes.z_lo) * (ph - 1)));
        fill(canvas, left - kTick, y, left, y + 1, kBlack);
        const std::string label = tick_label(v, z_decimals);
        draw_text(canvas, left - kTick - 3 - text_width(label, kScale), y - kCharHeight / 2, label, kScale, kBlack);
    }

    // Each colour bar: its ramp from hi at the top to lo at the bottom.
    for (const PlacedBar& p : placed) {
        const ColourBar& bar = *p.bar;
        std::vector<float> ramp(size_t(kBarWidth) * ph);
        for (int y = 0; y < ph; ++y)
            std::fill(&ramp[size_t(y) * kBarWidth], &ramp[size_t(y + 1) * kBarWidth],
                      bar.hi - (bar.hi - bar.lo) * float(y) / float(std::max(ph - 1, 1)));
        paste(canvas, colour_map(ramp, kBarWidth, ph, bar.lo, bar.hi, bar.ramp), p.x, top);
        frame(canvas, p.x, top, kBarWidth, ph);
        draw_text(canvas, p.x, top - kCharHeight - 6, bar.label, kScale, kBlack);
        for (double v : p.ticks) {
            const int y = top + int(std::lround((bar.hi - v) / (bar.hi - bar.lo) * (ph - 1)));
            fill(canvas, p.x + kBarWidth, y, p.x + kBarWidth + kTick, y + 1, kBlack);
            draw_text(canvas, p.x + kBarWidth + kTick + 3, y - kCharHeight / 2, tick_label(v, p.decimals), kScale,
                      kBlack);
        }
    }
    if (!caption.empty()) draw_text(canvas, left, canvas.height - kCharHeight - 8, caption, kScale, kBlack);
    return canvas;
}

Image framed_figure(const std::vector<Image>& panels, const std::vector<std::string>& titles, const SliceAxes& axes,
                    float value_lo, float value_hi, const std::string& value_label) {
    return framed_figure(panels, titles, axes, {ColourBar{panels.size() - 1, value_lo, value_hi, value_label}});
}

}  // namespace cli
