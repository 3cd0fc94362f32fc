// What a tp_scene* points to (full library only): the validated scene.
#pragma once

#include "bake/scene.h"

struct tp_scene {
    tetprobe::Scene scene;
};
