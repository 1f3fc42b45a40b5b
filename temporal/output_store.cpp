#include "temporal/output_store.h"

#include "temporal/taa_measure.h"

#include <fmt/format.h>

#include <atomic>

namespace kdop {
namespace {

// Generations are unique in the process, not per store: a DeviceFlip may serve one store after
// another, and keeps a reference's work by its generation alone.
std::uint64_t next_generation() {
    static std::atomic<std::uint64_t> last{0};
    return ++last;
}

} // namespace

OutputStore::Slot& OutputStore::renew(std::size_t slot) {
    if (slot >= slots_.size()) slots_.resize(slot + 1);
    Slot& s = slots_[slot];
    s.generation = next_generation();
    s.host.reset();
    return s;
}

Result<OutputStore::Slot*> OutputStore::find(FrameHandle handle) {
    if (!handle || handle.slot >= slots_.size() || slots_[handle.slot].generation != handle.generation)
        return fail(fmt::format("internal error: a stale frame handle (slot {}, generation {})", handle.slot,
                                handle.generation));
    return &slots_[handle.slot];
}

FrameHandle OutputStore::put(std::size_t slot, Image image) {
    Slot& s = renew(slot);
    s.host = std::move(image);
    return {slot, s.generation};
}

Result<FrameHandle> HostOutputStore::take_output(std::size_t slot, TaaResolve& resolve, std::size_t shader,
                                                 ColorRange range, std::string_view label) {
    auto output = within_range(resolve.take_output(shader), range, label);
    if (!output) return std::unexpected(output.error());
    return put(slot, std::move(*output));
}

Result<const Image*> HostOutputStore::image(FrameHandle handle) {
    auto s = find(handle);
    if (!s) return std::unexpected(s.error());
    return &*(*s)->host;
}

Result<FrameHandle> DeviceOutputStore::take_output(std::size_t slot, TaaResolve& resolve, std::size_t shader,
                                                   ColorRange range, std::string_view label) {
    using Input = DeviceFlip::Input;
    auto view = resolve.output_on_device(shader);
    if (!view) return std::unexpected(view.error());
    holding_[std::size_t(Input::test)] = {};
    auto outside = flip_.load(Input::test, *view, range == ColorRange::hdr, kOutputRounding);
    if (!outside) return std::unexpected(outside.error());
    if (*outside) {
        const DeviceFlip::Outside& o = **outside;
        auto why = outside_range(o.value, range, label, o.x, o.y);
        return fail(why ? *why
                        : fmt::format("internal error: {}: pixel ({}, {}) is outside the range on the device, not on "
                                      "the host",
                                      label, o.x, o.y));
    }
    if (slot >= buffers_.size()) buffers_.resize(slot + 1);
    if (!buffers_[slot].buffer()) {
        auto buffer = DeviceBuffer::create(flip_.context(), flip_.image_bytes(),
                                           VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                           DeviceBuffer::Memory::device, "an output kept for FLIP");
        if (!buffer) return std::unexpected(buffer.error());
        buffers_[slot] = std::move(*buffer);
    }
    if (auto ok = flip_.store(Input::test, buffers_[slot]); !ok) return std::unexpected(ok.error());
    const FrameHandle handle{slot, renew(slot).generation};
    holding_[std::size_t(Input::test)] = handle;
    return handle;
}

Result<const Image*> DeviceOutputStore::prepare(FrameHandle handle, DeviceFlip::Input input) {
    auto s = find(handle);
    if (!s) return std::unexpected(s.error());
    if ((*s)->host) return &*(*s)->host;
    FrameHandle& held = holding_[std::size_t(input)];
    if (held != handle) {
        held = {};
        if (auto ok = flip_.restore(buffers_[handle.slot], input); !ok) return std::unexpected(ok.error());
        held = handle;
    }
    return nullptr;
}

Result<const Image*> DeviceOutputStore::image(FrameHandle handle) {
    using Input = DeviceFlip::Input;
    auto s = find(handle);
    if (!s) return std::unexpected(s.error());
    if (!(*s)->host) {
        // Brought back through the pair's test image, where it is or where it is copied.
        auto on_device = prepare(handle, Input::test);
        if (!on_device) return std::unexpected(on_device.error());
        (*s)->host = flip_.loaded(Input::test);
    }
    return &*(*s)->host;
}

void DeviceOutputStore::let_go(FrameHandle handle) {
    auto s = find(handle);
    if (s) (*s)->host.reset();
}

} // namespace kdop
