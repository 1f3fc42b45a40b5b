#include "temporal/flip_evaluator.h"

namespace kdop {
namespace {

Result<FlipFigure> flip_figure(Result<FlipMap> ldr) {
    if (!ldr) return std::unexpected(ldr.error());
    return FlipFigure{ldr->mean, {}, std::move(ldr->error)};
}

Result<FlipFigure> flip_figure(Result<HdrFlipMaps> hdr) {
    if (!hdr) return std::unexpected(hdr.error());
    return FlipFigure{hdr->mean, std::move(hdr->range.note), std::move(hdr->error)};
}

// An evaluator of frames on the host: each pair fetched from its store, then measured by
// figure(), given the reference's generation as the key device FLIP keeps its work by.
class HostFrames : public FlipEvaluator {
public:
    explicit HostFrames(const ExposureOptions& exposures) : exposures_(exposures) {}
    OutputStore& store() override { return store_; }
    const ExposureOptions& exposures() const override { return exposures_; }

    Result<FlipFigure> evaluate(FrameHandle reference, FrameHandle test, ColorRange range, bool map) override {
        auto r = store_.image(reference);
        if (!r) return std::unexpected(r.error());
        auto t = store_.image(test);
        if (!t) return std::unexpected(t.error());
        return figure(**r, **t, reference.generation, range, map);
    }

protected:
    virtual Result<FlipFigure> figure(const Image& reference, const Image& test, DeviceFlip::ReferenceKey key,
                                      ColorRange range, bool map) = 0;
    ExposureOptions exposures_;

private:
    HostOutputStore store_;
};

class CpuFlipEvaluator final : public HostFrames {
public:
    CpuFlipEvaluator(const HdrFlip& flip, const ExposureOptions& exposures) : HostFrames(exposures), flip_(flip) {}

private:
    Result<FlipFigure> figure(const Image& reference, const Image& test, DeviceFlip::ReferenceKey, ColorRange range,
                              bool map) override {
        if (range == ColorRange::ldr) { // LdrFlip::mean is the mean_error of this map
            auto error = flip_.ldr().error_map(reference, test);
            if (!error) return std::unexpected(error.error());
            return FlipFigure{mean_error(*error), {}, map ? std::move(*error) : std::vector<float>{}};
        }
        auto maps = flip_.maps(reference, test, exposures_);
        if (!maps) return std::unexpected(maps.error());
        return FlipFigure{maps->mean, maps->range.note, map ? std::move(maps->error) : std::vector<float>{}};
    }

    const HdrFlip& flip_;
};

// Device FLIP over frames on the host: each pair uploaded, the reference's work kept while its
// generation is the last one's.
class DeviceFlipOnHost final : public HostFrames {
public:
    DeviceFlipOnHost(DeviceFlip& flip, const ExposureOptions& exposures) : HostFrames(exposures), flip_(flip) {}

private:
    Result<FlipFigure> figure(const Image& reference, const Image& test, DeviceFlip::ReferenceKey key, ColorRange range,
                              bool map) override {
        if (range == ColorRange::ldr) return flip_figure(flip_.ldr(reference, test, map, key));
        return flip_figure(flip_.hdr(reference, test, exposures_, map, key));
    }

    DeviceFlip& flip_;
};

// Device FLIP over outputs kept on the device: each loaded into FLIP's pair unless it is there;
// truths uploaded from the host, their work kept as on the host.
class DeviceFlipOnDevice final : public FlipEvaluator {
public:
    DeviceFlipOnDevice(DeviceFlip& flip, const ExposureOptions& exposures)
        : flip_(flip), exposures_(exposures), store_(flip) {}
    OutputStore& store() override { return store_; }
    const ExposureOptions& exposures() const override { return exposures_; }

    Result<FlipFigure> evaluate(FrameHandle reference, FrameHandle test, ColorRange range, bool map) override {
        using Input = DeviceFlip::Input;
        auto r = store_.prepare(reference, Input::reference);
        if (!r) return std::unexpected(r.error());
        auto t = store_.prepare(test, Input::test);
        if (!t) return std::unexpected(t.error());
        // What comes from the host is uploaded over the pair's image.
        if (*r) store_.pair_overwritten(Input::reference);
        if (*t) store_.pair_overwritten(Input::test);
        const DeviceFlip::ReferenceKey key = *r ? reference.generation : DeviceFlip::kNoKey;
        if (range == ColorRange::ldr) return flip_figure(flip_.ldr(*r, *t, map, key));
        return flip_figure(flip_.hdr(*r, *t, exposures_, map, key));
    }

private:
    DeviceFlip& flip_;
    ExposureOptions exposures_;
    DeviceOutputStore store_;
};

} // namespace

std::unique_ptr<FlipEvaluator> cpu_flip_evaluator(const HdrFlip& flip, const ExposureOptions& exposures) {
    return std::make_unique<CpuFlipEvaluator>(flip, exposures);
}

std::unique_ptr<FlipEvaluator> device_flip_evaluator(DeviceFlip& flip, const ExposureOptions& exposures,
                                                     OutputPlacement placement) {
    if (placement == OutputPlacement::host) return std::make_unique<DeviceFlipOnHost>(flip, exposures);
    return std::make_unique<DeviceFlipOnDevice>(flip, exposures);
}

} // namespace kdop
