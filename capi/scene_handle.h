// The opaque tp_scene: a bake-time scene (full library only).
#pragma once

#include "bake/scene.h"

struct tp_scene {
    tetprobe::Scene scene;
};
