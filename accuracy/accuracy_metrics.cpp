#include "accuracy/accuracy_metrics.h"

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>

namespace kdop {
namespace {

glm::dvec3 rgb(const glm::vec4& p) { return glm::dvec3(p); }

} // namespace

double pixel_magnitude(const glm::vec4& current) {
    return std::max({1.0, std::abs(double(current.x)), std::abs(double(current.y)), std::abs(double(current.z))});
}

std::vector<double> ideal_distances(const Image& current, const Image& history, std::span<const double> ideal_exits,
                                    const Image& clipped) {
    std::vector<double> distances(current.pixels.size());
    for (std::size_t i = 0; i < distances.size(); ++i) {
        const glm::dvec3 c = rgb(current.pixels[i]), h = rgb(history.pixels[i]);
        distances[i] =
            glm::distance(rgb(clipped.pixels[i]), c + ideal_exits[i] * (h - c)) / pixel_magnitude(current.pixels[i]);
    }
    return distances;
}

ClipAccuracy measure_accuracy(const Image& current, const Image& history, std::span<const double> ideal_exits,
                              const Image& clipped, std::span<const double> distances) {
    ClipAccuracy a;
    a.pixels = distances.size();
    if (distances.empty()) return a;
    double sum = 0;
    for (std::size_t i = 0; i < distances.size(); ++i) {
        sum += distances[i];
        const glm::dvec3 c = rgb(current.pixels[i]), h = rgb(history.pixels[i]);
        const double s = pixel_magnitude(current.pixels[i]);
        if ((1 - ideal_exits[i]) * glm::distance(h, c) > kOutsideHull * s) {
            ++a.outside;
            a.falsely_accepted += glm::distance(rgb(clipped.pixels[i]), h) <= kUnchanged * s;
        }
    }
    a.mean_dist = sum / double(distances.size());
    std::vector<double> sorted(distances.begin(), distances.end()); // partly, for the rank
    a.max_dist = *std::max_element(sorted.begin(), sorted.end());
    const std::size_t rank = static_cast<std::size_t>(std::ceil(0.95 * double(sorted.size()))) - 1;
    std::nth_element(sorted.begin(), sorted.begin() + rank, sorted.end());
    a.p95_dist = sorted[rank];
    return a;
}

Looser compare_distances(std::span<const double> a, std::span<const double> b) {
    Looser l;
    if (a.empty()) return l;
    std::size_t looser = 0;
    l.largest = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        looser += a[i] > b[i] + kSameDistance;
        l.largest = std::max(l.largest, a[i] - b[i]);
    }
    l.share = double(looser) / double(a.size());
    return l;
}

} // namespace kdop
