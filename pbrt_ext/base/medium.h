// Which media lie on the two sides of a surface (pbrt-v4's MediumInterface in base/medium.h).
// Media are indices into Scene::media; -1 is vacuum.
#pragma once

#include "pbrt_ext/pbrt.h"

namespace pbrt {

struct MediumInterface {
    MediumInterface() = default;
    PBRT_CPU_GPU explicit MediumInterface(int medium) : inside(medium), outside(medium) {}
    PBRT_CPU_GPU MediumInterface(int inside, int outside) : inside(inside), outside(outside) {}
    PBRT_CPU_GPU bool IsMediumTransition() const { return inside != outside; }
    bool operator==(const MediumInterface &) const = default;

    // inside: the side the surface normal points away from.
    int inside = -1, outside = -1;
};

}  // namespace pbrt
