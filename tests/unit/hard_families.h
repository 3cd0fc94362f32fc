// The hard-case families every exact-tessellation test runs on: random clouds, lattices plain, rotated
// and jittered, cospherical and cocircular sets, flat and tilted sets, a line, clusters, offsets,
// scales, merged duplicates, and the smallest sets (1, 2, 3 probes, a corridor).
#pragma once

#include "probe_families.h"

#include <random>
#include <string>
#include <vector>

namespace families {

inline ProbeSet cospherical(int r) {
    ProbeSet s{"integer sphere " + std::to_string(r) + " and its centre", {}};
    for (int x = -r; x <= r; ++x)
        for (int y = -r; y <= r; ++y)
            for (int z = -r; z <= r; ++z)
                if (x * x + y * y + z * z == r * r) s.add(100 + x, 200 + y, 300 + z);
    s.add(100, 200, 300);
    return s;
}

inline ProbeSet cocircular(int r) {
    ProbeSet s{"integer circle " + std::to_string(r) + " and its centre, tilted", {}};
    for (int x = -r; x <= r; ++x)
        for (int y = -r; y <= r; ++y)
            if (x * x + y * y == r * r) s.add(x, y, 2 * x - y);
    s.add(0, 0, 0);
    return s;
}

inline std::vector<ProbeSet> hard_families() {
    std::vector<ProbeSet> sets = {random_cloud(200, 1),
                                  random_cloud(60, 2, 0.5),
                                  lattice(2, 2, 2),
                                  lattice(3, 3, 3),
                                  lattice(5, 5, 5),
                                  lattice(8, 8, 8),
                                  lattice(12, 12, 12, 0.5),
                                  lattice(6, 6, 6, 1, 2.4e-7),
                                  lattice(7, 3, 2, 0.1),
                                  slab(8, 1e-3),
                                  plane(80, 5),
                                  tilted_plane_rounded(120, 6),
                                  racetrack(48),
                                  line(12),
                                  random_cloud(150, 11, 10, 1e3),
                                  random_cloud(150, 12, 10, 1e6),
                                  dense_room_in_a_level(21),
                                  random_cloud(150, 13, 1e-4),
                                  random_cloud(150, 14, 1e5),
                                  rotated_lattice(4, 1),
                                  rotated_lattice(7, 2),
                                  rotated_lattice(12, 1),
                                  rotated_lattice(6, 3, 1e6),
                                  cluster_in_a_level(300, 1e-2, 41),
                                  cluster_in_a_level(40, 1e-2, 42),
                                  cospherical(5),
                                  cospherical(9),
                                  cocircular(5),
                                  cocircular(25)};
    // Duplicates and near-duplicates (merged).
    ProbeSet duplicates = random_cloud(80, 10);
    std::mt19937 rng(10);
    for (int i = 0; i < 40; ++i) {
        const size_t j = rng() % 80;
        duplicates.add(duplicates.positions[3 * j] + (i % 2 ? 1e-6f : 0.0f), duplicates.positions[3 * j + 1],
                       duplicates.positions[3 * j + 2]);
    }
    duplicates.name = "duplicates";
    sets.push_back(duplicates);
    ProbeSet one{"1 probe", {}}, two{"2 probes", {}}, three{"3 probes", {}}, corridor{"3 in a corridor", {}};
    one.add(4, 5, 6);
    two.add(0, 0, 0), two.add(1, 2, 2);
    three.add(0, 0, 0), three.add(4, 0, 0), three.add(1, 3, 0);
    corridor.add(0, 1, 0), corridor.add(10, 1, 0), corridor.add(20, 1, 0);
    sets.insert(sets.end(), {one, two, three, corridor});
    return sets;
}

}  // namespace families
