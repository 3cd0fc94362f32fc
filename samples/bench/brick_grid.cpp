#include "brick_grid.h"

#include "apv_sh_encoding.h"
#include "dilated_grid.h"
#include "trilinear_blend.h"

#include "core/sh.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace bench {

namespace {

constexpr size_t kBrickBytes = BrickGrid::kBrickSamples * kApvRecordBytes;
constexpr size_t kEntriesPerTopBrick = 16 * 16 * 16;  // indirection entries under one top brick (4h each)
// The top level may take this share of the budget; level 1 then up to half of what remains.
constexpr double kTopShare = 0.3, kLevelOneShare = 0.5;
// A cell's lighting changes when its corners' luminance (any axis normal) spans more than this share of
// the level's mean.
constexpr double kChangeThreshold = 0.02;

double cell_size(double h, int level) { return h * (level == 0 ? 16 : level == 1 ? 4 : 1); }

const float kNormals[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};

double luminance(const float sh[27], const float n[3]) {
    float rgb[3];
    tetprobe::sh_eval_irradiance(sh, n, rgb);
    return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
}

// Largest spread over the 6 axis normals of the luminance at the 8 corners of cell (x, y, z) of a brick
// whose 125 samples' SH (27 floats each) are given.
double corner_spread(const std::vector<float>& sh, int x, int y, int z) {
    double spread = 0;
    for (const float* n : kNormals) {
        double lo = INFINITY, hi = -INFINITY;
        for (int c = 0; c < 8; ++c) {
            const size_t s = size_t(x + (c & 1)) + 5 * size_t(y + ((c >> 1) & 1)) + 25 * size_t(z + (c >> 2));
            const double e = luminance(&sh[27 * s], n);
            lo = std::min(lo, e), hi = std::max(hi, e);
        }
        spread = std::max(spread, hi - lo);
    }
    return spread;
}

}  // namespace

std::vector<float> BrickGrid::sample_positions(int level, const double min[3]) const {
    const double cell = cell_size(h_, level);
    std::vector<float> p;
    p.reserve(3 * kBrickSamples);
    for (int z = 0; z < kSamples; ++z)
        for (int y = 0; y < kSamples; ++y)
            for (int x = 0; x < kSamples; ++x) {
                p.push_back(float(min[0] + cell * x));
                p.push_back(float(min[1] + cell * y));
                p.push_back(float(min[2] + cell * z));
            }
    return p;
}

uint32_t BrickGrid::add_brick(int level, const double min[3], const std::vector<float>& sh) {
    const uint32_t index = uint32_t(bricks_.size());
    if (index > UINT16_MAX) throw std::runtime_error("BrickGrid: more than 65,536 bricks");
    bricks_.push_back({{float(min[0]), float(min[1]), float(min[2])}, level});
    records_.resize(records_.size() + kBrickBytes);
    uint8_t* r = &records_[size_t(index) * kBrickBytes];
    for (size_t s = 0; s < kBrickSamples; ++s) apv_encode(&sh[27 * s], r + s * kApvRecordBytes);
    ++bricks_per_level_[level];
    set_indirection(level, min, index);
    return index;
}

void BrickGrid::set_indirection(int level, const double min[3], uint32_t brick) {
    const int span = level == 0 ? 16 : level == 1 ? 4 : 1;  // entries per axis under the brick
    int first[3];
    for (int k = 0; k < 3; ++k) first[k] = int(std::lround((min[k] - lo_[k]) / (4 * h_)));
    for (int z = first[2]; z < first[2] + span; ++z)
        for (int y = first[1]; y < first[1] + span; ++y)
            for (int x = first[0]; x < first[0] + span; ++x)
                indirection_[size_t(x) + size_t(indirection_dims_[0]) * (size_t(y) + size_t(indirection_dims_[1]) * size_t(z))] =
                    uint16_t(brick);
}

BrickGrid::BrickGrid(const float lo[3], const float hi[3], size_t budget_bytes, const BrickBuildHooks& hooks) {
    double extent[3], largest = 0;
    for (int k = 0; k < 3; ++k) lo_[k] = lo[k], extent[k] = std::max(double(hi[k]) - lo[k], 1e-3), largest = std::max(largest, extent[k]);
    auto top_cost = [&](double h, int t[3]) {
        size_t n = 1;
        for (int k = 0; k < 3; ++k) t[k] = std::max(1, int(std::ceil(extent[k] / (64 * h) - 1e-9))), n *= size_t(t[k]);
        return n * (kBrickBytes + 2 * kEntriesPerTopBrick) + kHeaderBytes;
    };
    // The finest h whose top level fits its share; one top brick over the whole box at least.
    h_ = largest / 64;
    if (top_cost(h_, top_) > budget_bytes)
        throw std::runtime_error("the smallest brick grid (one top brick and its indirection, " +
                                 std::to_string(top_cost(h_, top_)) + " bytes) exceeds the budget");
    for (double h = h_; h > largest * 1e-4; h *= 0.97) {
        int t[3];
        if (top_cost(h, t) > kTopShare * double(budget_bytes)) break;
        h_ = h;
    }
    top_cost(h_, top_);
    for (int k = 0; k < 3; ++k) indirection_dims_[k] = 16 * top_[k], lo_f_[k] = float(lo_[k]);
    for (int l = 0; l < kLevels; ++l) inv_cell_[l] = float(1.0 / cell_size(h_, l));
    inv_entry_ = float(1.0 / (4 * h_));
    indirection_.assign(size_t(indirection_dims_[0]) * indirection_dims_[1] * indirection_dims_[2], 0);

    // Level 0: the lattice of every top brick's samples, baked and dilated as one, then cut into bricks.
    const int lattice[3] = {4 * top_[0] + 1, 4 * top_[1] + 1, 4 * top_[2] + 1};
    std::vector<float> positions;
    for (int z = 0; z < lattice[2]; ++z)
        for (int y = 0; y < lattice[1]; ++y)
            for (int x = 0; x < lattice[0]; ++x) {
                const int i[3] = {x, y, z};
                for (int k = 0; k < 3; ++k) positions.push_back(float(lo_[k] + cell_size(h_, 0) * i[k]));
            }
    auto bake_valid = [&](const std::vector<float>& p, std::vector<uint8_t>* valid) {
        *valid = hooks.valid(p);
        std::vector<float> kept;
        for (size_t i = 0; i < valid->size(); ++i)
            if ((*valid)[i]) kept.insert(kept.end(), &p[3 * i], &p[3 * i] + 3);
        const std::vector<float> baked = kept.empty() ? std::vector<float>() : hooks.bake(kept);
        samples_baked_ += kept.size() / 3;
        std::vector<float> sh(27 * valid->size(), 0.0f);
        for (size_t i = 0, j = 0; i < valid->size(); ++i)
            if ((*valid)[i]) std::copy(&baked[27 * j], &baked[27 * j] + 27, &sh[27 * i]), ++j;
        return sh;
    };
    std::vector<uint8_t> valid;
    std::vector<float> lattice_sh = bake_valid(positions, &valid);
    dilate_probes(lattice, valid, lattice_sh);
    std::vector<std::vector<float>> brick_sh;  // float SH of each brick while building
    for (int bz = 0; bz < top_[2]; ++bz)
        for (int by = 0; by < top_[1]; ++by)
            for (int bx = 0; bx < top_[0]; ++bx) {
                std::vector<float> sh(27 * kBrickSamples);
                for (int z = 0; z < 5; ++z)
                    for (int y = 0; y < 5; ++y)
                        for (int x = 0; x < 5; ++x) {
                            const size_t from = size_t(4 * bx + x) + size_t(lattice[0]) * (size_t(4 * by + y) + size_t(lattice[1]) * size_t(4 * bz + z));
                            std::copy(&lattice_sh[27 * from], &lattice_sh[27 * from] + 27, &sh[27 * (size_t(x) + 5 * size_t(y) + 25 * size_t(z))]);
                        }
                const double min[3] = {lo_[0] + 64 * h_ * bx, lo_[1] + 64 * h_ * by, lo_[2] + 64 * h_ * bz};
                add_brick(0, min, sh);
                brick_sh.push_back(std::move(sh));
            }

    // Levels 1 and 2: refine cells near a surface whose lighting changes, largest change first.
    for (int level = 1; level < kLevels; ++level) {
        const size_t used = bytes();
        if (used >= budget_bytes) break;
        const size_t allowance = level == 1 ? size_t(kLevelOneShare * double(budget_bytes - used)) : budget_bytes - used;
        const size_t affordable = allowance / kBrickBytes;
        struct Candidate {
            double change;
            double min[3];
        };
        std::vector<Candidate> candidates;
        const double parent_cell = cell_size(h_, level - 1);
        for (size_t b = 0; b < bricks_.size(); ++b) {
            if (bricks_[b].level != level - 1) continue;
            for (int z = 0; z < 4; ++z)
                for (int y = 0; y < 4; ++y)
                    for (int x = 0; x < 4; ++x) {
                        Candidate c;
                        c.change = corner_spread(brick_sh[b], x, y, z) / hooks.mean_irradiance;
                        if (c.change <= kChangeThreshold) continue;
                        const int i[3] = {x, y, z};
                        float centre[3];
                        for (int k = 0; k < 3; ++k) {
                            c.min[k] = double(bricks_[b].min[k]) + parent_cell * i[k];
                            centre[k] = float(c.min[k] + 0.5 * parent_cell);
                        }
                        if (!hooks.near_surface(centre, float(parent_cell * 0.8660254))) continue;
                        candidates.push_back(c);
                    }
        }
        std::stable_sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) { return a.change > b.change; });
        if (candidates.size() > affordable) candidates.resize(affordable);
        if (candidates.empty()) continue;
        positions.clear();
        for (const Candidate& c : candidates) {
            const std::vector<float> p = sample_positions(level, c.min);
            positions.insert(positions.end(), p.begin(), p.end());
        }
        std::vector<float> sh = bake_valid(positions, &valid);
        const int brick_dims[3] = {5, 5, 5};
        for (size_t c = 0; c < candidates.size(); ++c) {
            std::vector<float> own(sh.begin() + std::ptrdiff_t(27 * kBrickSamples * c), sh.begin() + std::ptrdiff_t(27 * kBrickSamples * (c + 1)));
            const std::vector<uint8_t> own_valid(valid.begin() + std::ptrdiff_t(kBrickSamples * c), valid.begin() + std::ptrdiff_t(kBrickSamples * (c + 1)));
            if (std::find(own_valid.begin(), own_valid.end(), uint8_t(1)) == own_valid.end()) {
                // Nothing valid: the parent's values at the samples (the indirection still names the parent).
                for (size_t s = 0; s < kBrickSamples; ++s) interpolate(&positions[3 * (kBrickSamples * c + s)], &own[27 * s]);
            } else {
                dilate_probes(brick_dims, own_valid, own);
            }
            add_brick(level, candidates[c].min, own);
            brick_sh.push_back(std::move(own));
        }
    }
}

void BrickGrid::interpolate(const float position[3], float out_sh[27]) const {
    size_t entry = 0, scale = 1;
    for (int k = 0; k < 3; ++k) {
        const float u = std::min(std::max((position[k] - lo_f_[k]) * inv_entry_, 0.0f), float(indirection_dims_[k] - 1));
        entry += size_t(u) * scale;
        scale *= size_t(indirection_dims_[k]);
    }
    const uint32_t b = indirection_[entry];
    const Brick& brick = bricks_[b];
    const float inv = inv_cell_[brick.level];
    float frac[3];
    size_t sample = 0;
    const size_t stride[3] = {1, 5, 25};
    for (int k = 0; k < 3; ++k) {
        const float v = std::min(std::max((position[k] - brick.min[k]) * inv, 0.0f), 4.0f);
        const int base = std::min(int(v), 3);
        frac[k] = v - float(base);
        sample += size_t(base) * stride[k];
    }
    static constexpr size_t kCorner[8] = {0 * kApvRecordBytes,  1 * kApvRecordBytes,  5 * kApvRecordBytes,
                                          6 * kApvRecordBytes,  25 * kApvRecordBytes, 26 * kApvRecordBytes,
                                          30 * kApvRecordBytes, 31 * kApvRecordBytes};
    trilinear_apv(&records_[size_t(b) * kBrickBytes + sample * kApvRecordBytes], kCorner, frac, out_sh);
}

size_t BrickGrid::bytes() const { return records_.size() + 2 * indirection_.size() + kHeaderBytes; }

size_t BrickGrid::resident_bytes() const { return bytes() + bricks_.size() * sizeof(Brick); }

std::string BrickGrid::summary() const {
    char text[160];
    std::snprintf(text, sizeof text, "finest cell %.3g m; bricks %zu / %zu / %zu (cells x16, x4, x1); indirection %d x %d x %d",
                  h_, bricks_per_level_[0], bricks_per_level_[1], bricks_per_level_[2], indirection_dims_[0],
                  indirection_dims_[1], indirection_dims_[2]);
    return text;
}

}  // namespace bench
