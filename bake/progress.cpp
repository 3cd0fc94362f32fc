#include "bake/progress.h"

#include "core/error.h"

#include <algorithm>
#include <string>

namespace tetprobe {

void Progress::report(double fraction, const char* stage) const {
    if (!callback) return;
    const double f = double(from) + (double(to) - double(from)) * std::min(std::max(fraction, 0.0), 1.0);
    if (callback(user, float(f), stage) != 0)
        throw Error(Status::cancelled, std::string("cancelled by the progress callback during ") + stage);
}

Progress Progress::part(double a, double b) const {
    Progress sub = *this;
    sub.from = float(double(from) + (double(to) - double(from)) * a);
    sub.to = float(double(from) + (double(to) - double(from)) * b);
    return sub;
}

}  // namespace tetprobe
