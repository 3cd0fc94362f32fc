// Peer of the benchmark (never linked into a tetprobe library): an adaptive brick grid like Unreal's
// Volumetric Lightmap. Bricks of 4 x 4 x 4 cells hold 5 x 5 x 5 samples (their border samples too, so
// trilinear filtering never leaves a brick), at three levels of cell size 16h, 4h and h. The top level
// tiles the box; a cell of a level-0 or level-1 brick that a surface passes through (within its bounding
// sphere) and whose corners' lighting differs is refined into a brick of the next level, cells of largest
// lighting change first, while the budget lasts. An indirection grid at the finest bricks' size (4h) names
// the brick covering each of its cells (2 bytes an entry). Samples inside geometry are dilated from their
// valid neighbours (a brick with none takes its parent's values there). SH in APV's 8-bit encoding (32
// bytes a sample). A query: one indirection read, one brick's 8 samples, trilinear.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace bench {

struct BrickBuildHooks {
    // Bakes positions (3 floats each) and returns 27 floats each.
    std::function<std::vector<float>(const std::vector<float>&)> bake;
    // 1 per position that is not inside geometry.
    std::function<std::vector<uint8_t>(const std::vector<float>&)> valid;
    // True when a surface lies within `radius` of the point.
    std::function<bool(const float point[3], float radius)> near_surface;
    double mean_irradiance = 1;  // the level's mean: lighting change is judged relative to it
};

class BrickGrid {
public:
    static constexpr int kCells = 4, kSamples = 5, kLevels = 3;
    static constexpr size_t kBrickSamples = 125;
    static constexpr size_t kHeaderBytes = 64;  // box, finest cell size, dims of the top level and indirection

    // Builds the grid over [lo, hi] within budget_bytes (bricks x 4,000 + indirection x 2 + header); throws
    // std::runtime_error when even one top brick and its indirection do not fit.
    BrickGrid(const float lo[3], const float hi[3], size_t budget_bytes, const BrickBuildHooks& hooks);

    void interpolate(const float position[3], float out_sh[27]) const;
    size_t bytes() const;           // what ships (see above)
    size_t resident_bytes() const;  // plus this implementation's per-brick origin and level (16 bytes)
    size_t bricks(int level) const { return bricks_per_level_[level]; }
    size_t samples_baked() const { return samples_baked_; }
    size_t indirection_entries() const { return indirection_.size(); }
    double finest_cell() const { return h_; }
    std::string summary() const;

private:
    struct Brick {
        float min[3];
        int32_t level;
    };
    // Adds a brick of `level` with its min corner; its samples' SH (27 floats each, 125) are encoded.
    uint32_t add_brick(int level, const double min[3], const std::vector<float>& sh);
    std::vector<float> sample_positions(int level, const double min[3]) const;
    void set_indirection(int level, const double min[3], uint32_t brick);

    double lo_[3], h_ = 1;
    int top_[3];        // top-level bricks per axis
    int indirection_dims_[3];
    float inv_cell_[kLevels];  // 1 / cell size per level
    float lo_f_[3], inv_entry_;
    std::vector<uint16_t> indirection_;
    std::vector<Brick> bricks_;
    std::vector<uint8_t> records_;  // 125 x 32 bytes per brick
    size_t bricks_per_level_[kLevels] = {0, 0, 0};
    size_t samples_baked_ = 0;
};

}  // namespace bench
