// TEMPORARY STUB (replaced by the real LDR-FLIP)
#pragma once
#include "image.h"
#include "result.h"
#include <vector>
namespace kdop {
struct ViewingConditions { double distance_m = 0.7, display_width_m = 0.7, display_width_px = 3840; };
double pixels_per_degree(const ViewingConditions&);
class LdrFlip {
public:
    explicit LdrFlip(double ppd) : ppd_(ppd) {}
    Result<double> mean(const Image& reference, const Image& test) const;
private:
    double ppd_;
};
}
