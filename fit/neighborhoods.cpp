#include "fit/neighborhoods.h"

#include "generator/variant_spec.h"
#include "images/random.h"

#include <algorithm>
#include <string_view>
#include <unordered_map>

namespace kdop {
namespace {

// Neighborhoods made one at a time: a repeat of an earlier one only counts.
class NeighborhoodGatherer {
public:
    // Into `reuse`'s storage: a frame gathered again on each pass of a search writes where the last
    // one was instead of faulting in hundreds of megabytes of new pages.
    NeighborhoodGatherer(std::size_t size, std::size_t total, Neighborhoods reuse = {}) : out_(std::move(reuse)) {
        out_.size = size;
        out_.total = total;
        out_.points.clear();
        out_.repeats.clear();
        // Room for every neighborhood, so the keys (views of the points' bytes) stay where they are.
        out_.points.reserve(total * out_.size);
        seen_.reserve(total);
    }
    void add(std::span<const glm::dvec3> neighborhood) {
        const std::size_t start = out_.points.size();
        out_.points.insert(out_.points.end(), neighborhood.begin(), neighborhood.end());
        const std::string_view key(reinterpret_cast<const char*>(out_.points.data() + start),
                                   out_.size * sizeof(glm::dvec3));
        const auto [at, added] = seen_.try_emplace(key, static_cast<std::uint32_t>(out_.repeats.size()));
        if (added) {
            out_.repeats.push_back(1);
        } else {
            ++out_.repeats[at->second];
            out_.points.resize(start);
        }
    }
    // `shrink`: give back the room repeats left unused (a copy of every point), for neighborhoods
    // that are kept.
    Neighborhoods finish(bool shrink = true) {
        seen_ = {};
        if (shrink) out_.points.shrink_to_fit();
        return std::move(out_);
    }

private:
    Neighborhoods out_;
    std::unordered_map<std::string_view, std::uint32_t> seen_; // a distinct neighborhood's bytes -> its index
};

// The neighborhood of pixel (x, y), clamped to the edge, appended to `out`.
void append_neighborhood(const Image& image, std::uint32_t x, std::uint32_t y, std::span<const glm::ivec2> offsets,
                         std::vector<glm::dvec3>& out) {
    for (const glm::ivec2& o : offsets) out.emplace_back(glm::dvec3(image.clamped(int(x) + o.x, int(y) + o.y)));
}

} // namespace

Neighborhoods gather_neighborhoods(std::span<const Image> images, Neighborhood shape) {
    Neighborhoods out;
    gather_neighborhoods(images, shape, out);
    // Kept: the room that repeats left unused is given back, where it is worth a copy.
    if (out.points.size() < out.points.capacity() / 4 * 3) out.points.shrink_to_fit();
    return out;
}

void gather_neighborhoods(std::span<const Image> images, Neighborhood shape, Neighborhoods& out) {
    const std::span<const glm::ivec2> offsets = neighborhood_offsets(shape);
    std::size_t total = 0;
    for (const Image& image : images) total += std::size_t(image.width) * image.height;
    NeighborhoodGatherer gather(offsets.size(), total, std::move(out));
    std::vector<glm::dvec3> one;
    for (const Image& image : images)
        for (std::uint32_t y = 0; y < image.height; ++y)
            for (std::uint32_t x = 0; x < image.width; ++x) {
                one.clear();
                append_neighborhood(image, x, y, offsets, one);
                gather.add(one);
            }
    out = gather.finish(false);
}

NeighborhoodSampler::NeighborhoodSampler(Neighborhood shape, std::span<const std::uint64_t> frame_pixels,
                                         std::size_t count, std::uint64_t seed)
    : shape_(shape), seed_(seed), share_(frame_pixels.size()), pixels_(frame_pixels.begin(), frame_pixels.end()),
      drawn_(frame_pixels.size()) {
    std::uint64_t total = 0;
    for (std::uint64_t pixels : frame_pixels) total += pixels;
    count = std::size_t(std::min<std::uint64_t>(count, total));
    // Each frame's share of `count`, by its pixel count, the remainders to the largest fractions
    // (the earlier frame on a tie), so the shares add up to `count` exactly.
    std::vector<std::pair<double, std::size_t>> fractions;
    std::size_t given = 0;
    for (std::size_t i = 0; i < frame_pixels.size(); ++i) {
        const double exact = double(count) * double(frame_pixels[i]) / double(total);
        share_[i] = std::size_t(exact);
        given += share_[i];
        fractions.emplace_back(-(exact - double(share_[i])), i);
    }
    std::sort(fractions.begin(), fractions.end());
    for (std::size_t k = 0; given < count; ++k, ++given) ++share_[fractions[k].second];
}

std::size_t NeighborhoodSampler::drawn_points(std::size_t frame) const {
    return std::size_t(std::min<std::uint64_t>(share_[frame], pixels_[frame])) * neighborhood_offsets(shape_).size();
}

void NeighborhoodSampler::add(std::size_t frame, const Image& image) {
    const std::size_t share = share_[frame];
    std::vector<glm::dvec3>& out = drawn_[frame];
    out.clear();
    if (share == 0) return;
    // Frame 0 draws with the seed itself, the others with generators of their own, so a frame
    // draws the same pixels whoever reads it.
    Random random(seed_ + frame * 0x9e3779b97f4a7c15ull);
    // The pixels by luminance (then position, so ties are ordered), cut into `share` strata of
    // equal size; one pixel drawn from each.
    std::vector<std::pair<float, std::uint32_t>> by_luminance(std::size_t(image.width) * image.height);
    for (std::uint32_t p = 0; p < by_luminance.size(); ++p) {
        const glm::vec4& c = image.pixels[p];
        by_luminance[p] = {0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b, p};
    }
    std::sort(by_luminance.begin(), by_luminance.end());
    const std::size_t pixels = by_luminance.size();
    const std::span<const glm::ivec2> offsets = neighborhood_offsets(shape_);
    out.reserve(std::min(share, pixels) * offsets.size());
    for (std::size_t k = 0; k < std::min(share, pixels); ++k) {
        const std::size_t first = k * pixels / share, end = (k + 1) * pixels / share;
        const std::size_t pick = first + std::min(end - first - 1, std::size_t(random.uniform() * double(end - first)));
        const std::uint32_t p = by_luminance[pick].second;
        append_neighborhood(image, p % image.width, p / image.width, offsets, out);
    }
}

Neighborhoods NeighborhoodSampler::finish() {
    const std::size_t size = neighborhood_offsets(shape_).size();
    std::size_t total = 0;
    for (const std::vector<glm::dvec3>& points : drawn_) total += points.size() / size;
    NeighborhoodGatherer gather(size, total);
    for (const std::vector<glm::dvec3>& points : drawn_)
        for (std::size_t i = 0; i + size <= points.size(); i += size) gather.add({points.data() + i, size});
    drawn_ = {};
    return gather.finish();
}

Neighborhoods sample_neighborhoods(std::span<const Image> images, Neighborhood shape, std::size_t count,
                                   std::uint64_t seed) {
    std::vector<std::uint64_t> pixels;
    for (const Image& image : images) pixels.push_back(std::uint64_t(image.width) * image.height);
    NeighborhoodSampler sampler(shape, pixels, count, seed);
    for (std::size_t i = 0; i < images.size(); ++i) sampler.add(i, images[i]);
    return sampler.finish();
}

} // namespace kdop
