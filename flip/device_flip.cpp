#include "flip/device_flip.h"

#include "generator/runnable_variant.h"
#include "runtime/vulkan_error.h"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <string>
#include <tuple>

namespace kdop {
namespace {

constexpr std::uint32_t kLocalSize = 64; // the template's local_size_x

std::uint32_t ceil_div(std::uint32_t a, std::uint32_t b) { return (a + b - 1) / b; }
constexpr VkFormat kPlaneFormat = VK_FORMAT_R32G32B32A32_SFLOAT; // the template's rgba32f images

// The template's push constants, as std430 lays them out.
struct Parameters {
    std::uint32_t width, height;
    float exposure_scale, exposure_where;
    std::uint32_t tone_mapper, maps;
    std::uint32_t first_image = 0;
    std::uint32_t hdr = 0;
    float rounding = 0;
    std::uint32_t prefix = 0;
};
// Parameters::maps, the template's kMap* bits.
constexpr std::uint32_t kMapFirstExposure = 1, kMapExposure = 2, kMapTerms = 4;

// One pass's dispatch of x by y by z workgroups: its pipeline, its set and `p` as its push constants.
void record_dispatch(VkCommandBuffer cb, const Kernel& k, VkDescriptorSet set, const Parameters& p, std::uint32_t x,
                     std::uint32_t y, std::uint32_t z) {
    vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_COMPUTE, k.pipeline());
    vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_COMPUTE, k.layout(), 0, 1, &set, 0, nullptr);
    vkCmdPushConstants(cb, k.layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0,
                       std::min<std::uint32_t>(sizeof p, k.push_constant_size()), &p);
    vkCmdDispatch(cb, x, y, z);
}

// Every write of one dispatch visible to the next one's reads and writes.
void compute_barrier(VkCommandBuffer cb, VkAccessFlags src_access, VkPipelineStageFlags src_stage,
                     VkAccessFlags dst_access, VkPipelineStageFlags dst_stage) {
    VkMemoryBarrier b{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    b.srcAccessMask = src_access;
    b.dstAccessMask = dst_access;
    vkCmdPipelineBarrier(cb, src_stage, dst_stage, 0, 1, &b, 0, nullptr, 0, nullptr);
}

// Per pixel: both images' inputs (a vec4 each) and filtered planes (two vec4 each), the four maps.
constexpr std::uint64_t kInputBytes = 2 * 16, kHorizontalBytes = 2 * 32, kMapBytes = 4 * 4;
// The luminance pass's largest luminance and its 65,536 counts (the template's Histogram).
constexpr std::size_t kHistogramCounts = 65536, kHistogramBytes = 4 * (1 + kHistogramCounts);
// The luminance pass's `prefix` for its first count, by the top 16 bits.
constexpr std::uint32_t kTopBits = 0xffffffff;

} // namespace

std::uint64_t DeviceFlip::bytes(std::uint32_t width, std::uint32_t height) {
    const std::uint64_t n = std::uint64_t(width) * height;
    return n * (kInputBytes + kHorizontalBytes + kMapBytes) + 4ull * height + kHistogramBytes;
}

Result<void> DeviceFlip::check_limits(const Context& context, std::uint32_t width, std::uint32_t height) {
    if (width == 0 || height == 0) return fail(fmt::format("FLIP of an empty {}x{} image", width, height));
    const auto& limits = context.properties().limits;
    // The largest grid is the vertical pass's on a GPU (runs of 1): a row of workgroups per image row.
    if (ceil_div(width, kLocalSize) > limits.maxComputeWorkGroupCount[0] || height > limits.maxComputeWorkGroupCount[1])
        return fail(fmt::format("FLIP of {}x{}: {} dispatches at most {}x{} workgroups of {} pixels", width, height,
                                context.device_name(), limits.maxComputeWorkGroupCount[0],
                                limits.maxComputeWorkGroupCount[1], kLocalSize));
    if (2ull * width * height > limits.maxTexelBufferElements)
        return fail(fmt::format("FLIP of {}x{}: the pair is {} texels, and {} takes at most {} in a texel buffer",
                                width, height, 2ull * width * height, context.device_name(),
                                limits.maxTexelBufferElements));
    const std::uint64_t maps = std::uint64_t(width) * height * kMapBytes;
    if (maps > limits.maxStorageBufferRange)
        return fail(fmt::format("FLIP of {}x{}: its maps need a storage buffer of {} bytes, and {} allows at most {}",
                                width, height, maps, context.device_name(), limits.maxStorageBufferRange));
    if (width > limits.maxImageDimension2D || height > limits.maxImageDimension2D)
        return fail(fmt::format("FLIP of {}x{}: {} allows at most {} pixels on an image's side", width, height,
                                context.device_name(), limits.maxImageDimension2D));
    return {};
}

Result<std::unique_ptr<DeviceFlip>> DeviceFlip::create(const Context& context, double pixels_per_degree,
                                                       std::uint32_t width, std::uint32_t height) {
    if (auto ok = check_pixels_per_degree(pixels_per_degree); !ok) return std::unexpected(ok.error());
    if (auto ok = check_limits(context, width, height); !ok) return std::unexpected(ok.error());
    std::unique_ptr<DeviceFlip> f(new DeviceFlip(context, pixels_per_degree, width, height));
    f->runs_ = {flip_run_length(context, kHorizontal), flip_run_length(context, kVertical)};
    const LdrFlip cpu(pixels_per_degree); // the kernels and constants, as the CPU code computes them
    for (int pass = 0; pass < kPasses; ++pass) {
        auto shader = build_flip_pass(cpu, pass, flip_run_length(context, pass));
        if (!shader) return std::unexpected(shader.error());
        auto kernel = Kernel::create(context, (*shader)->variant());
        if (!kernel) return std::unexpected(kernel.error());
        f->shaders_[std::size_t(pass)] = std::move(*shader);
        f->kernels_[std::size_t(pass)] = std::move(*kernel);
    }

    const std::uint64_t n = std::uint64_t(width) * height;
    const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    using Memory = DeviceBuffer::Memory;
    struct Allocation {
        DeviceBuffer* buffer;
        std::uint64_t size;
        VkBufferUsageFlags usage;
        Memory memory;
        const char* what;
    } allocations[] = {
        {&f->inputs_, n * kInputBytes,
         VK_BUFFER_USAGE_STORAGE_TEXEL_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
         Memory::host, "FLIP's inputs"},
        {&f->maps_, n * kMapBytes, storage, Memory::host, "FLIP's maps"},
        {&f->row_sums_, 4ull * height, storage, Memory::host, "FLIP's row sums"},
        {&f->outside_, 8, storage, Memory::host, "FLIP's count of values outside the range"},
        {&f->histogram_, kHistogramBytes, storage, Memory::host, "FLIP's counts of luminances"},
    };
    for (const Allocation& a : allocations) {
        auto buffer = DeviceBuffer::create(context, a.size, a.usage, a.memory, a.what);
        if (!buffer) return std::unexpected(buffer.error());
        *a.buffer = std::move(*buffer);
    }
    VkBufferViewCreateInfo view{VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO};
    view.buffer = f->inputs_.buffer();
    view.format = kPlaneFormat;
    view.range = n * kInputBytes;
    KDOP_VK_TRY(vkCreateBufferView(context.device(), &view, nullptr, &f->inputs_view_));
    auto horizontal = DeviceImage::create(context, width, height, 4, kPlaneFormat, VK_IMAGE_USAGE_STORAGE_BIT,
                                          "FLIP's filtered planes");
    if (!horizontal) return std::unexpected(horizontal.error());
    f->horizontal_ = std::move(*horizontal);
    auto commands = OneShotCommands::create(context);
    if (!commands) return std::unexpected(commands.error());
    f->commands_ = std::move(*commands);
    // texelFetch ignores filtering and addressing; a combined image sampler still needs a sampler.
    VkSamplerCreateInfo sampler{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    sampler.magFilter = sampler.minFilter = VK_FILTER_NEAREST;
    sampler.addressModeU = sampler.addressModeV = sampler.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    KDOP_VK_TRY(vkCreateSampler(context.device(), &sampler, nullptr, &f->sampler_));

    // One set per pass, written once: each reads binding 0 and writes binding 1, a buffer, an image
    // or (the inputs) a texel buffer. The load pass's source (its binding 0) is written per load,
    // and it counts into binding 2.
    std::vector<const Kernel*> kernels;
    for (const auto& kernel : f->kernels_) kernels.push_back(kernel.get());
    auto sets = KernelSets::create(context, kernels);
    if (!sets) return std::unexpected(sets.error());
    f->kernel_sets_ = std::move(*sets);
    const BoundTexels inputs{f->inputs_view_};
    const BoundImage planes{f->horizontal_.view()};
    auto buffer = [](const DeviceBuffer& b) { return BoundBuffer{b.buffer()}; };
    const std::vector<Bound> bindings[kPasses] = {{{0, inputs}, {1, planes}},
                                                  {{0, planes}, {1, buffer(f->maps_)}},
                                                  {{0, buffer(f->maps_)}, {1, buffer(f->row_sums_)}},
                                                  {{1, inputs}, {2, buffer(f->outside_)}},
                                                  {{0, inputs}, {1, buffer(f->histogram_)}}};
    for (int pass = 0; pass < kPasses; ++pass) {
        const Kernel& kernel = *f->kernels_[std::size_t(pass)];
        const std::size_t expected = pass == kLoad ? 3 : 2;
        if (kernel.bindings().size() != expected)
            return fail(fmt::format("internal error: {} has {} bindings, not {}", kernel.name(),
                                    kernel.bindings().size(), expected));
        auto set = f->kernel_sets_.allocate(kernel);
        if (!set) return std::unexpected(set.error());
        f->sets_[std::size_t(pass)] = *set;
        if (auto ok = f->kernel_sets_.write(kernel, *set, bindings[pass]); !ok) return std::unexpected(ok.error());
    }
    return f;
}

DeviceFlip::DeviceFlip(const Context& context, double ppd, std::uint32_t width, std::uint32_t height)
    : context_(context), ppd_(ppd), width_(width), height_(height) {}

DeviceFlip::~DeviceFlip() {
    vkDeviceWaitIdle(context_.device());
    vkDestroyBufferView(context_.device(), inputs_view_, nullptr);
    vkDestroySampler(context_.device(), sampler_, nullptr);
}

Result<void> DeviceFlip::check_pair(const Image* reference, const Image* test,
                                    Result<void> (*check_values)(const Image&, const std::string&),
                                    ReferenceKey key) const {
    // A reference whose planes the last evaluation left was checked then.
    const bool checked = key != kNoKey && reference_planes_ && reference_planes_->key == key;
    for (auto [image, what] : {std::pair{reference, "reference image"}, std::pair{test, "test image"}}) {
        if (!image || (image == reference && checked)) continue;
        if (image->width != width_ || image->height != height_)
            return fail(fmt::format("{}: {}x{}, but this FLIP evaluator was made for {}x{}", what, image->width,
                                    image->height, width_, height_));
        if (auto ok = check_values(*image, what); !ok) return ok;
    }
    return {};
}

Result<DeviceFlip::Evaluation> DeviceFlip::evaluate(const Image* reference, const Image* test,
                                                    std::optional<ToneMapper> tone_mapper,
                                                    std::span<const Exposure> exposures, ReadBack read_back,
                                                    ReferenceKey key) {
    const std::uint32_t mapper = !tone_mapper                        ? 0u
                                 : *tone_mapper == ToneMapper::aces  ? 1u
                                 : *tone_mapper == ToneMapper::hable ? 2u
                                                                     : 3u;
    // The reference's upload and horizontal filters are kept where its key is the last one's and
    // the planes still hold it at this exposure (ReferenceKey, in the header).
    const bool keep_reference =
        reference && key != kNoKey && exposures.size() == 1 && reference_planes_ && reference_planes_->key == key &&
        reference_planes_->exposure_scale == exposures[0].scale && reference_planes_->tone_mapper == mapper;
    reference_planes_.reset(); // until this evaluation has run
    const std::size_t n = std::size_t(width_) * height_;
    auto* inputs = static_cast<std::byte*>(inputs_.mapped());
    if (reference && !keep_reference) std::memcpy(inputs, reference->pixels.data(), n * 16);
    if (test) std::memcpy(inputs + n * 16, test->pixels.data(), n * 16);

    const std::uint32_t groups_x = ceil_div(width_, kLocalSize);
    const VkAccessFlags shader_rw = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
    const VkPipelineStageFlags compute = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
    auto ran = commands_->run([&](VkCommandBuffer cb) {
        // The planes are written before they are read in every evaluation, so what they held is
        // dropped, except the reference's where they are kept.
        image_barrier(cb, horizontal_.image(), keep_reference ? VK_IMAGE_LAYOUT_GENERAL : VK_IMAGE_LAYOUT_UNDEFINED,
                      VK_IMAGE_LAYOUT_GENERAL, keep_reference ? shader_rw : 0, shader_rw,
                      keep_reference ? compute : VkPipelineStageFlags(VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT), compute,
                      horizontal_.layers());
        auto dispatch = [&](int pass, const Parameters& p, std::uint32_t x, std::uint32_t y, std::uint32_t z) {
            record_dispatch(cb, *kernels_[std::size_t(pass)], sets_[std::size_t(pass)], p, x, y, z);
            compute_barrier(cb, VK_ACCESS_SHADER_WRITE_BIT, compute, shader_rw, compute);
        };
        // The maps the vertical pass writes: what is read back, and, from the second exposure on,
        // the error only where it grows.
        const std::uint32_t maps = (read_back == ReadBack::error_and_exposure ? kMapExposure : 0u) |
                                   (read_back == ReadBack::terms ? kMapTerms : 0u);
        for (std::size_t i = 0; i < exposures.size(); ++i) {
            const Exposure& e = exposures[i];
            const std::uint32_t first_image = keep_reference ? 1u : 0u; // image 0 is the reference
            const Parameters p{width_,     height_, e.scale, e.where, mapper, maps | (i == 0 ? kMapFirstExposure : 0u),
                               first_image};
            dispatch(kHorizontal, p, ceil_div(ceil_div(width_, runs_[0]), kLocalSize), height_, 2 - first_image);
            dispatch(kVertical, p, groups_x, ceil_div(height_, runs_[1]), 1);
        }
        dispatch(kRowSums, Parameters{width_, height_, 1, 0, 0, 0}, ceil_div(height_, kLocalSize), 1, 1);
        compute_barrier(cb, VK_ACCESS_SHADER_WRITE_BIT, compute, VK_ACCESS_HOST_READ_BIT, VK_PIPELINE_STAGE_HOST_BIT);
    });
    if (!ran) return std::unexpected(ran.error());
    if (exposures.size() == 1 && reference && key != kNoKey)
        reference_planes_ = ReferencePlanes{key, exposures[0].scale, mapper};

    Evaluation out;
    const auto* rows = static_cast<const float*>(row_sums_.mapped());
    double sum = 0;
    for (std::uint32_t y = 0; y < height_; ++y) sum += double(rows[y]);
    out.mean = sum / double(n);
    const auto* maps = static_cast<const float*>(maps_.mapped());
    auto map = [&](int k) { return std::vector<float>(maps + std::size_t(k) * n, maps + std::size_t(k + 1) * n); };
    if (read_back != ReadBack::mean) out.error = map(0);
    if (read_back == ReadBack::error_and_exposure || read_back == ReadBack::terms) out.exposure = map(1);
    if (read_back == ReadBack::terms) {
        out.color = map(2);
        out.feature = map(3);
    }
    return out;
}

Result<double> DeviceFlip::mean(const Image& reference, const Image& test) {
    auto evaluated = ldr(reference, test, false);
    if (!evaluated) return std::unexpected(evaluated.error());
    return evaluated->mean;
}

Result<FlipMap> DeviceFlip::ldr(const Image& reference, const Image& test, bool read_map, ReferenceKey key) {
    return ldr(&reference, &test, read_map, key);
}

Result<FlipMap> DeviceFlip::ldr(const Image* reference, const Image* test, bool read_map, ReferenceKey key) {
    if (auto ok = check_pair(reference, test, check_ldr_image, key); !ok) return std::unexpected(ok.error());
    const Exposure one[1];
    auto e = evaluate(reference, test, std::nullopt, one, read_map ? ReadBack::error : ReadBack::mean, key);
    if (!e) return std::unexpected(e.error());
    return FlipMap{e->mean, std::move(e->error)};
}

Result<FlipTerms> DeviceFlip::terms(const Image& reference, const Image& test) {
    if (auto ok = check_pair(&reference, &test, check_ldr_image, kNoKey); !ok) return std::unexpected(ok.error());
    const Exposure one[1];
    auto e = evaluate(&reference, &test, std::nullopt, one, ReadBack::terms, kNoKey);
    if (!e) return std::unexpected(e.error());
    return FlipTerms{std::move(e->color), std::move(e->feature), std::move(e->error)};
}

Result<HdrFlipMaps> DeviceFlip::hdr(const Image& reference, const Image& test, const ExposureOptions& options,
                                    bool read_maps, ReferenceKey key) {
    return hdr(&reference, &test, options, read_maps, key);
}

Result<HdrFlipMaps> DeviceFlip::hdr_over(const Image* reference, const Image* test, const ExposureRange& range,
                                         ToneMapper tone_mapper, bool read_maps, ReferenceKey key) {
    std::vector<Exposure> exposures(std::size_t(range.count));
    for (int i = 0; i < range.count; ++i)
        exposures[std::size_t(i)] = {std::pow(2.0f, range.exposure(i)),
                                     range.count == 1 ? 0.0f : float(i) / float(range.count - 1)};
    auto e = evaluate(reference, test, tone_mapper, exposures,
                      read_maps ? ReadBack::error_and_exposure : ReadBack::mean, key);
    if (!e) return std::unexpected(e.error());
    HdrFlipMaps out;
    out.range = range;
    out.mean = e->mean;
    out.error = std::move(e->error);
    out.exposure = std::move(e->exposure);
    return out;
}

Result<std::optional<DeviceFlip::Outside>> DeviceFlip::load(Input input, VkImageView source, bool hdr, float rounding) {
    if (input == Input::reference) reference_planes_.reset();
    auto* outside = static_cast<std::uint32_t*>(outside_.mapped());
    outside[0] = 0;          // the count
    outside[1] = UINT32_MAX; // the first, as atomicMin finds it
    // The set is not in use: every run waits for its commands to finish.
    const Bound image[] = {{0, BoundImage{source, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, sampler_}}};
    if (auto ok = kernel_sets_.write(*kernels_[kLoad], sets_[kLoad], image); !ok) return std::unexpected(ok.error());
    const Parameters p{width_, height_, 1, 0, 0, 0, input == Input::test ? 1u : 0u, hdr ? 1u : 0u, rounding};
    auto ran = commands_->run([&](VkCommandBuffer cb) {
        record_dispatch(cb, *kernels_[kLoad], sets_[kLoad], p, ceil_div(width_, kLocalSize), height_, 1);
        // For the evaluation's passes and copies, and the host's count.
        compute_barrier(cb, VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                        VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_HOST_READ_BIT,
                        VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT |
                            VK_PIPELINE_STAGE_HOST_BIT);
    });
    if (!ran) return std::unexpected(ran.error());
    if (outside[0] == 0) return std::nullopt;
    Outside o;
    o.count = outside[0];
    o.x = outside[1] % width_;
    o.y = outside[1] / width_;
    // An image outside is left as it was: its first pixel's values, for the message.
    const std::size_t n = std::size_t(width_) * height_;
    std::memcpy(&o.value,
                static_cast<const std::byte*>(inputs_.mapped()) +
                    (std::size_t(input == Input::test) * n + outside[1]) * 16,
                16);
    return o;
}

Image DeviceFlip::loaded(Input input) const {
    Image image(width_, height_);
    const std::size_t n = std::size_t(width_) * height_;
    std::memcpy(image.pixels.data(),
                static_cast<const std::byte*>(inputs_.mapped()) + std::size_t(input == Input::test) * n * 16, n * 16);
    return image;
}

Result<void> DeviceFlip::store(Input input, const DeviceBuffer& buffer) { return copy(input, buffer, true); }

Result<void> DeviceFlip::restore(const DeviceBuffer& buffer, Input input) {
    if (input == Input::reference) reference_planes_.reset();
    return copy(input, buffer, false);
}

Result<void> DeviceFlip::copy(Input input, const DeviceBuffer& buffer, bool into_buffer) {
    const VkDeviceSize bytes = image_bytes(), half = bytes * VkDeviceSize(input == Input::test);
    if (buffer.size() < bytes)
        return fail(fmt::format("internal error: a buffer of {} bytes for an image of {}", buffer.size(), bytes));
    auto copied = commands_->run([&](VkCommandBuffer cb) {
        // After every pass, load and host write before it; before every pass and host read after it.
        const VkAccessFlags all = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_HOST_READ_BIT |
                                  VK_ACCESS_HOST_WRITE_BIT | VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
        const VkPipelineStageFlags stages =
            VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_HOST_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT;
        compute_barrier(cb, all, stages, all, stages);
        const VkBufferCopy region{into_buffer ? half : 0, into_buffer ? 0 : half, bytes};
        vkCmdCopyBuffer(cb, into_buffer ? inputs_.buffer() : buffer.buffer(),
                        into_buffer ? buffer.buffer() : inputs_.buffer(), 1, &region);
        compute_barrier(cb, all, stages, all, stages);
    });
    if (!copied) return std::unexpected(copied.error());
    return {};
}

Result<HdrFlipMaps> DeviceFlip::hdr(const Image* reference, const Image* test, const ExposureOptions& options,
                                    bool read_maps, ReferenceKey key) {
    if (auto ok = check_pair(reference, test, check_hdr_image, key); !ok) return std::unexpected(ok.error());
    // Each image's luminances where it is: on the host, or (loaded) on the device.
    auto of = [&](const Image* image, Input input) -> LuminancesSource {
        return
            [this, image, input]() -> Result<Luminances> { return image ? luminances_of(*image) : luminances(input); };
    };
    auto range = exposure_range(options, of(reference, Input::reference), of(test, Input::test));
    if (!range) return std::unexpected(range.error());
    return hdr_over(reference, test, *range, options.tone_mapper, read_maps, key);
}

Result<Luminances> DeviceFlip::luminances(Input input) {
    const std::uint64_t n = std::uint64_t(width_) * height_;
    auto* histogram = static_cast<std::uint32_t*>(histogram_.mapped());
    // One count of the luminances: by their top 16 bits (kTopBits), or by their low 16 bits those
    // whose top 16 bits are `prefix`.
    auto count = [&](std::uint32_t prefix) -> Result<void> {
        std::memset(histogram, 0, kHistogramBytes);
        const Parameters p{width_, height_, 1, 0, 0, 0, input == Input::test ? 1u : 0u, 0, 0, prefix};
        auto ran = commands_->run([&](VkCommandBuffer cb) {
            record_dispatch(cb, *kernels_[kLuminance], sets_[kLuminance], p, ceil_div(width_, kLocalSize), height_, 1);
            compute_barrier(cb, VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                            VK_ACCESS_HOST_READ_BIT, VK_PIPELINE_STAGE_HOST_BIT);
        });
        if (!ran) return std::unexpected(ran.error());
        return {};
    };
    // The bucket of `counts` that holds the `k`th value in sorted order (from 0), `k` left as its
    // place within the bucket.
    auto bucket = [](const std::vector<std::uint32_t>& counts, std::uint64_t& k) -> std::optional<std::uint32_t> {
        for (std::uint32_t b = 0; b < counts.size(); k -= counts[b++])
            if (k < counts[b]) return b;
        return std::nullopt;
    };
    auto counted = [&] { return std::vector<std::uint32_t>(histogram + 1, histogram + 1 + kHistogramCounts); };
    if (auto ok = count(kTopBits); !ok) return std::unexpected(ok.error());
    const std::vector<std::uint32_t> top = counted();
    Luminances out;
    out.largest = std::bit_cast<float>(histogram[0]);
    // The `k`th luminance in sorted order: its top 16 bits' bucket, then its low 16 bits in there.
    auto select = [&](std::uint64_t k) -> Result<float> {
        const auto high = bucket(top, k);
        if (!high) return fail(fmt::format("internal error: the device counted fewer than {} luminances", n));
        if (auto ok = count(*high); !ok) return std::unexpected(ok.error());
        const auto low = bucket(counted(), k);
        if (!low) return fail(fmt::format("internal error: the device's counts of luminances disagree"));
        return std::bit_cast<float>(*high << 16 | *low);
    };
    auto median = select(n / 2);
    if (!median) return std::unexpected(median.error());
    out.median = *median;
    if (!(out.median > 0.0f) && out.largest > 0.0f) {
        // Black pixels (luminance 0, the least a checked image holds) come first in sorted order:
        // the others' median lies half of the rest after them.
        if (auto ok = count(0); !ok) return std::unexpected(ok.error());
        const std::uint64_t black = histogram[1];
        median = select(black + (n - black) / 2);
        if (!median) return std::unexpected(median.error());
        out.median = *median;
        out.median_of_lit = true;
    }
    return out;
}

} // namespace kdop
