#include "generator/reflection_json.h"

#include "core/upscale_settings.h"

#include "generator/manifest.h"
#include "generator/provenance.h"
#include "generator/spirv_module.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#ifndef KDOP_VERSION
#error "KDOP_VERSION must be defined by the build"
#endif

namespace kdop {
namespace {

using Json = nlohmann::ordered_json; // keys in the order written: the same entries, the same bytes

// "combined image sampler" -> "combined_image_sampler", the C++ registry's enumerator.
std::string type_name(DescriptorType type) {
    std::string name = to_string(type);
    for (char& c : name)
        if (c == ' ') c = '_';
    return name;
}

Json axis_set_json(const VariantSpec& spec) {
    const AxisSet& set = spec.set;
    Json axes = Json::array();
    for (const Axis& axis : set.axes) axes.push_back({axis.direction.x, axis.direction.y, axis.direction.z});
    return {{"name", set.name},
            {"file", axis_file_name(set)},
            {"provenance", set.provenance},
            {"color_map", set.color_map ? Json(to_string(*set.color_map)) : Json(nullptr)},
            {"axes", std::move(axes)}};
}

Json entry_json(const BuiltVariant& v, const std::optional<std::string>& spirv_file) {
    const ShaderInterface& in = v.interface;
    const std::uint32_t stage_bit = vulkan_stage_bit(in.stage);
    Json bindings = Json::array();
    for (const BindingInfo& b : in.bindings)
        bindings.push_back({{"set", b.set},
                            {"binding", b.binding},
                            {"name", b.name},
                            {"type", type_name(b.type)},
                            {"count", b.count},
                            {"stages", stage_bit},
                            {"block_size", b.block_size},
                            {"format", b.format}});
    // What the source declares and the SPIR-V lacks (unused_resources.h), so a reader sees why a
    // binding it expected is not above.
    Json unused = Json::array();
    for (const DeclaredResource& r : v.unused_resources)
        unused.push_back({{"name", r.name}, {"type", r.type ? type_name(*r.type) : "push_constants"}});
    Json members = Json::array();
    for (const PushConstantInfo& p : in.push_constants)
        members.push_back({{"name", p.name}, {"offset", p.offset}, {"size", p.size}});

    Json entry = {
        {"name", v.name},
        {"kind", v.spec.mode == Mode::shader ? "shader" : "variant"},
        {"stage", to_string(in.stage)},
        {"entry_point", in.entry_point},
        {"local_size", {in.local_size[0], in.local_size[1], in.local_size[2]}},
        {"bindings", std::move(bindings)},
        {"unused_resources", std::move(unused)},
        {"push_constants",
         {{"size", in.push_constant_size},
          {"stages", in.push_constant_size ? stage_bit : 0u},
          {"members", std::move(members)}}},
        {"color_outputs", in.color_output_count},
        {"spirv",
         {{"file", spirv_file ? Json(*spirv_file) : Json(nullptr)},
          {"words", v.spirv.size()},
          {"bytes", v.spirv.size() * 4},
          {"fnv1a64", fmt::format("{:016x}", spirv_hash(v.spirv))},
          {"target_env", to_string(v.spec.target_env)}}},
    };
    if (v.spec.mode == Mode::shader) {
        entry["clip"] = nullptr;
    } else {
        const bool baseline = v.spec.set.name.empty(); // gather-n9, copy: cost baselines, no axis set
        entry["clip"] = {
            {"mode", to_string(v.spec.mode)},       {"neighborhood", to_string(v.spec.neighborhood)},
            {"form", to_string(v.spec.form)},       {"numerics", to_string(v.spec.numerics)},
            {"axis_count", v.spec.set.axes.size()}, {"axis_set", baseline ? Json(nullptr) : axis_set_json(v.spec)}};
    }
    return entry;
}

// A float as JSON: the decimal that reads back as the same float (0.1, not 0.10000000149011612).
Json float_json(float value) { return std::stod(fmt::format("{}", value)); }

Json resolve_json(const ResolveSettings& r) {
    return {{"gamma", float_json(r.gamma)},
            {"current_weight", float_json(r.current_weight)},
            {"color_map", color_map_text(r)},
            {"history_filter", to_string(r.history_filter)},
            {"dilate_motion", r.dilate_motion},
            {"upscale", !r.upscaling ? Json(nullptr)
                                     : Json{{"filter", to_string(r.upscale_filter)},
                                            {"sample_distance", to_string(r.sample_distance)},
                                            {"box_scale", to_string(r.box_scale)}}}};
}

} // namespace

std::string reflection_json(std::span<const BuiltVariant> entries,
                            const std::function<std::optional<std::string>(const BuiltVariant&)>& spirv_file,
                            const std::optional<ResolveSettings>& resolve) {
    Json list = Json::array();
    for (const BuiltVariant& v : entries) list.push_back(entry_json(v, spirv_file ? spirv_file(v) : std::nullopt));
    const Json document = {{"format", "kdop-reflection"},
                           {"version", kReflectionFormatVersion},
                           {"generator", fmt::format("kdop-gen {}", KDOP_VERSION)},
                           {"resolve", resolve ? resolve_json(*resolve) : Json(nullptr)},
                           {"entries", std::move(list)}};
    // Every text in it is checked where it is read (axis files by line, shader names by file), so
    // nothing here should be other than UTF-8; should something still be, it is written as U+FFFD
    // rather than thrown at the end of the run, after all the work and before any file is written.
    return document.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

} // namespace kdop
