// Where a measurement keeps the frames FLIP compares: each frame's truth and every shader's output
// and previous output. A frame is named by a handle: the slot it lies in and the generation of
// what the slot holds, new with every image put there, so a handle kept past a change of its slot
// is stale and refused, and two handles with one generation hold the same pixels (what device FLIP
// keeps work by: DeviceFlip::ReferenceKey).
//
// Two places hold them. On the host (HostOutputStore) every output is read back and checked there
// (within_range). On the device (DeviceOutputStore) each output is checked and moved onto its
// range where the resolve leaves it (DeviceFlip::load) and kept in a buffer of that device; it comes
// to the host only when an observer asks for it (image()). Which one a measurement uses is the FLIP
// evaluator's choice (temporal/flip_evaluator.h); the measurement's loop is the same for both.
#pragma once

#include "core/result.h"
#include "flip/device_flip.h"
#include "images/image.h"
#include "runtime/device_buffer.h"
#include "sequence/frame_source.h"
#include "temporal/taa_resolve.h"

#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

namespace kdop {

struct FrameHandle {
    std::size_t slot = 0;
    std::uint64_t generation = 0; // 0: no frame
    explicit operator bool() const { return generation != 0; }
    friend bool operator==(const FrameHandle&, const FrameHandle&) = default;
};

class OutputStore {
public:
    virtual ~OutputStore() = default;

    // Whether the resolve must read its outputs back for take_output (TaaResolve::advance_all's
    // read_outputs): the host's store checks and keeps them there.
    virtual bool reads_back() const = 0;

    // Puts `image`, a frame from the host (a truth, a picture's frame), into `slot`.
    FrameHandle put(std::size_t slot, Image image);
    // Puts shader `shader`'s output of the frame `resolve` resolved last into `slot`, checked and
    // moved onto `range` as within_range does (temporal/taa_measure.h), its error naming `label`.
    virtual Result<FrameHandle> take_output(std::size_t slot, TaaResolve& resolve, std::size_t shader, ColorRange range,
                                            std::string_view label) = 0;
    // The image `handle` names, on the host: valid until its slot changes or let_go(). An error for
    // a stale handle, or where the image cannot come back.
    virtual Result<const Image*> image(FrameHandle handle) = 0;
    // Frees the host's copy of what image() brought back from the device (nothing where the host
    // is where the frame is kept): an observer's read-back held no longer than it needs it.
    virtual void let_go(FrameHandle) {}

protected:
    struct Slot {
        std::uint64_t generation = 0;
        std::optional<Image> host; // on the host: put() there, or taken there, or brought back
    };
    // `slot`, made where it is new, with a new generation and nothing in it.
    Slot& renew(std::size_t slot);
    // The slot `handle` names, or an error where the handle is stale.
    Result<Slot*> find(FrameHandle handle);
    std::vector<Slot> slots_;
};

// Every frame on the host.
class HostOutputStore final : public OutputStore {
public:
    bool reads_back() const override { return true; }
    Result<FrameHandle> take_output(std::size_t slot, TaaResolve& resolve, std::size_t shader, ColorRange range,
                                    std::string_view label) override;
    Result<const Image*> image(FrameHandle handle) override;
};

// The outputs on `flip`'s device, in buffers of their own; truths on the host, where they come
// from. `flip` must outlive the store, and take its loads and copies through it alone, so that
// what it says its pair holds (holding()) stays true.
class DeviceOutputStore final : public OutputStore {
public:
    explicit DeviceOutputStore(DeviceFlip& flip) : flip_(flip) {}

    bool reads_back() const override { return false; }
    Result<FrameHandle> take_output(std::size_t slot, TaaResolve& resolve, std::size_t shader, ColorRange range,
                                    std::string_view label) override;
    Result<const Image*> image(FrameHandle handle) override;
    void let_go(FrameHandle handle) override;

    // What FLIP evaluates: `handle`'s image on the host, or, where it is on the device alone, null,
    // with it loaded into `input` of FLIP's pair (copied there unless it is there already).
    Result<const Image*> prepare(FrameHandle handle, DeviceFlip::Input input);
    // Forgets what the pair holds: an evaluation with images from the host wrote over it.
    void pair_overwritten(DeviceFlip::Input input) { holding_[std::size_t(input)] = {}; }

private:
    DeviceFlip& flip_;
    std::vector<DeviceBuffer> buffers_; // by slot: the outputs' on the device
    FrameHandle holding_[2];            // what FLIP's reference and test hold, where a slot's output
};

} // namespace kdop
