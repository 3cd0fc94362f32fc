// What a tp_store* points to: the validated, immutable run-time store.
#pragma once

#include "core/store.h"

#include <memory>

struct tp_store {
    std::unique_ptr<tetprobe::Store> store;
};
