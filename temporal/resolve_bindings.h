// A renderer's own TAA or TAAU resolve declared by role: the map `kdop taa --resolve-bindings`
// reads names, for each of the shader's resources, push-constant members and uniform-block members
// ("uniforms": "<block>.<member>"), what kdop fills it with, and the conventions the shader expects
// of its motion. bind() checks the map against the
// shader's reflection (the registry's, kdop/variant.h), so a role that is missing, names a resource
// the shader lacks or has the wrong type is refused before any frame, naming the shader's
// resource, the role and what it expected. The format's schema is
// docs/resolve-bindings.schema.json; examples/engine_resolve ships a map for each resolve there.
//
//     {
//       "format": "kdop-resolve-bindings", "version": 1,
//       "resources": {"color_frame": "current", "history_frame": "history",
//                     "motion_frame": "motion", "rectified_history": "output"},
//       "push_constants": {"current_weight": "current_weight", "jitter": "jitter"},
//       "motion": {"units": "pixels", "points_to": "previous", "y_axis": "down"}
//     }
#pragma once

#include "core/result.h"
#include "sequence/sequence.h" // MotionConvention

#include <kdop/variant.h>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace kdop {

// What kdop binds to one of the shader's resources.
enum class ResourceRole : std::uint8_t {
    current, // this frame's color, at the input size (sampled)
    history, // the last frame's output, at the output size (sampled)
    output,  // this frame's output, written: rgba32f or rgba16f (a storage image)
    motion,  // this frame's motion, at the input size (sampled; the map's "motion" says its convention)
    depth,   // this frame's depth, at the input size (sampled)
    sampler, // a sampler for separate textures (HLSL's SamplerState): linear, clamped to the edge
};

// What kdop writes into one of the shader's push-constant members.
enum class ValueRole : std::uint8_t {
    current_weight,  // float: the current frame's share of the blend; 1 on a frame that starts a history
    gamma,           // float: the variance clip's width (the variant's push constant)
    jitter,          // vec2: where this frame's input samples lie, in input pixels (i + 0.5 + jitter)
    input_size,      // vec2: the input's width and height in pixels
    output_size,     // vec2: the output's
    frame_index,     // uint: the frame's index in the sequence
    reset,           // uint: 1 on a frame that starts a history (the first, a camera cut), else 0
    exposure,        // float: the frame's exposure multiplier (1 where the source gives none)
    sample_distance, // float: the clip's sample distance in input pixels (--upscale-sample-distance)
};

const char* to_string(ResourceRole role);
const char* to_string(ValueRole role);

// The factors that turn kdop's motion (input pixels, y down, pointing to the previous position)
// into what a shader of `convention` reads (sequence.h's, the map's "motion": the inverse of
// canonical_motion), for an input of width x height.
struct MotionScale {
    float x = 1, y = 1;
};
MotionScale motion_scale(const MotionConvention& convention, std::uint32_t width, std::uint32_t height);

struct ResolveBindings {
    std::string file;                                              // the map's path, as given: what errors name
    std::vector<std::pair<std::string, ResourceRole>> resources;   // the shader's name, its role
    std::vector<std::pair<std::string, ValueRole>> push_constants; // the member's name, its role
    std::vector<std::pair<std::string, ValueRole>> uniforms;       // "<block>.<member>", its role
    MotionConvention motion;                                       // as sequence.json's "motion" spells it
};

// A member of one of the shader's uniform blocks (a cbuffer), as its reflection gives it: the
// registry records a block's size alone, so build_bound_resolve passes these from the build.
struct UniformMember {
    std::string block; // the block's binding name (DescriptorBinding::name)
    std::string name;
    std::uint32_t offset, size;
};

// The map in `text`, read from `file` (which errors name, with the key at fault): unknown keys,
// roles and values are refused, as is a role given to two names.
Result<ResolveBindings> parse_resolve_bindings(std::string_view text, const std::string& file);
Result<ResolveBindings> read_resolve_bindings(const std::filesystem::path& file);

// The map checked against `shader`'s reflection: each role's binding or push-constant member.
struct BoundResolve {
    struct Resource {
        ResourceRole role;
        const DescriptorBinding* binding;
    };
    struct Value {
        ValueRole role;
        const PushConstantMember* member;
    };
    // A uniform block's member: where in the block kdop writes the role's value.
    struct Uniform {
        ValueRole role;
        const DescriptorBinding* block;
        std::uint32_t offset, size;
    };
    std::vector<Resource> resources; // a uniform block is not one: its members are uniforms
    std::vector<Value> values;
    std::vector<Uniform> uniforms;
    MotionConvention motion;
    const DescriptorBinding* find(ResourceRole role) const;
};

// Refuses, naming the map, the shader and the resource: a name the shader does not have; a resource
// of the wrong type for its role (a sampled image for current, history, motion and depth; a storage
// image of rgba32f or rgba16f for the output; a sampler for sampler); a push-constant or uniform
// member of the wrong size (the reflection records sizes, not scalar types: 4 bytes for a float or
// uint, 8 for a vec2); a resource or member of the shader the map gives no role (kdop could not
// fill it); a role given twice across push_constants and uniforms; and a map without current,
// history or output. `uniform_members`: the members of the shader's uniform blocks. `shader` must
// outlive the result.
Result<BoundResolve> bind(const ResolveBindings& map, const Variant& shader,
                          std::span<const UniformMember> uniform_members = {});

} // namespace kdop
