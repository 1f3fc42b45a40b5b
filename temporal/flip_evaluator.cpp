#include "temporal/flip_evaluator.h"

namespace kdop {
namespace {

Result<FlipFigure> figure(Result<FlipMap> ldr) {
    if (!ldr) return std::unexpected(ldr.error());
    return FlipFigure{ldr->mean, {}, std::move(ldr->error)};
}

Result<FlipFigure> figure(Result<HdrFlipMaps> hdr) {
    if (!hdr) return std::unexpected(hdr.error());
    return FlipFigure{hdr->mean, std::move(hdr->range.note), std::move(hdr->error)};
}

class CpuFlipEvaluator final : public FlipEvaluator {
public:
    CpuFlipEvaluator(const HdrFlip& flip, const ExposureOptions& exposures) : flip_(flip), exposures_(exposures) {}
    OutputStore& store() override { return store_; }
    const ExposureOptions& exposures() const override { return exposures_; }

    Result<FlipFigure> evaluate(FrameHandle reference, FrameHandle test, ColorRange range, bool map) override {
        auto r = store_.image(reference);
        if (!r) return std::unexpected(r.error());
        auto t = store_.image(test);
        if (!t) return std::unexpected(t.error());
        if (range == ColorRange::ldr) { // LdrFlip::mean is the mean_error of this map
            auto error = flip_.ldr().error_map(**r, **t);
            if (!error) return std::unexpected(error.error());
            return FlipFigure{mean_error(*error), {}, map ? std::move(*error) : std::vector<float>{}};
        }
        auto maps = flip_.maps(**r, **t, exposures_);
        if (!maps) return std::unexpected(maps.error());
        return FlipFigure{maps->mean, maps->range.note, map ? std::move(maps->error) : std::vector<float>{}};
    }

private:
    const HdrFlip& flip_;
    ExposureOptions exposures_;
    HostOutputStore store_;
};

// Device FLIP over frames on the host: each pair uploaded, the reference's work kept while its
// generation is the last one's.
class DeviceFlipOnHost final : public FlipEvaluator {
public:
    DeviceFlipOnHost(DeviceFlip& flip, const ExposureOptions& exposures) : flip_(flip), exposures_(exposures) {}
    OutputStore& store() override { return store_; }
    const ExposureOptions& exposures() const override { return exposures_; }

    Result<FlipFigure> evaluate(FrameHandle reference, FrameHandle test, ColorRange range, bool map) override {
        auto r = store_.image(reference);
        if (!r) return std::unexpected(r.error());
        auto t = store_.image(test);
        if (!t) return std::unexpected(t.error());
        if (range == ColorRange::ldr) return figure(flip_.ldr(**r, **t, map, reference.generation));
        return figure(flip_.hdr(**r, **t, exposures_, map, reference.generation));
    }

private:
    DeviceFlip& flip_;
    ExposureOptions exposures_;
    HostOutputStore store_;
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
        if (range == ColorRange::ldr) return figure(flip_.ldr(*r, *t, map, key));
        return figure(flip_.hdr(*r, *t, exposures_, map, key));
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
