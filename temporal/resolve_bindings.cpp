#include "temporal/resolve_bindings.h"

#include "core/read_file.h"
#include "core/shown_text.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <initializer_list>

namespace kdop {
namespace {

using json = nlohmann::json;

constexpr std::array kResourceRoles = {ResourceRole::current, ResourceRole::history, ResourceRole::output,
                                       ResourceRole::motion,  ResourceRole::depth,   ResourceRole::sampler};
constexpr std::array kValueRoles = {ValueRole::current_weight, ValueRole::gamma,       ValueRole::jitter,
                                    ValueRole::input_size,     ValueRole::output_size, ValueRole::frame_index,
                                    ValueRole::reset,          ValueRole::exposure,    ValueRole::sample_distance};

// The bytes a push-constant member of `role` holds: a float or uint, or a vec2.
std::uint32_t value_size(ValueRole role) {
    return role == ValueRole::jitter || role == ValueRole::input_size || role == ValueRole::output_size ? 8 : 4;
}

// "a, b and c" of the names `all` gives for `roles`.
template <class Role, std::size_t N>
std::string role_list(const std::array<Role, N>& roles) {
    std::vector<std::string> names;
    for (Role r : roles) names.emplace_back(to_string(r));
    return fmt::format("{}", fmt::join(names, ", "));
}

template <class Role, std::size_t N>
std::optional<Role> role_named(const std::array<Role, N>& roles, std::string_view name) {
    for (Role r : roles)
        if (name == to_string(r)) return r;
    return std::nullopt;
}

struct MapReader {
    const std::string& file;

    Error error(std::string_view where, std::string_view what) const {
        return {fmt::format("{}: {}: {}", file, where, what)};
    }

    Result<void> known_keys(const json& object, std::initializer_list<std::string_view> allowed,
                            std::string_view where) const {
        for (const auto& [key, value] : object.items())
            if (std::find(allowed.begin(), allowed.end(), key) == allowed.end())
                return std::unexpected(error(where, fmt::format("unknown key \"{}\" (the keys here: {})",
                                                                shown_text(key, 60), fmt::join(allowed, ", "))));
        return {};
    }

    // `object[key]`'s names and roles, each role once: the shader's names are its keys.
    template <class Role, std::size_t N>
    Result<std::vector<std::pair<std::string, Role>>> roles(const json& root, const char* key,
                                                            const std::array<Role, N>& all) const {
        std::vector<std::pair<std::string, Role>> out;
        const auto it = root.find(key);
        if (it == root.end()) return out;
        if (!it->is_object())
            return std::unexpected(error(key, "expected an object of the shader's names and their roles"));
        for (const auto& [name, value] : it->items()) {
            const std::string where = fmt::format("{}.{}", key, shown_text(name, 60));
            const json& given = value;
            const std::optional<Role> role =
                given.is_string() ? role_named(all, given.get<std::string>()) : std::nullopt;
            if (!role)
                return std::unexpected(
                    error(where, fmt::format("{} is not a role; the roles here: {}",
                                             given.is_string() ? "\"" + shown_text(given.get<std::string>(), 60) + "\""
                                                               : std::string("a ") + given.type_name(),
                                             role_list(all))));
            for (const auto& [other, taken] : out)
                if (taken == *role)
                    return std::unexpected(error(where, fmt::format("the role {} is also given to \"{}\"; kdop fills "
                                                                    "one resource or member with each",
                                                                    to_string(*role), shown_text(other, 60))));
            out.emplace_back(name, *role);
        }
        return out;
    }

    // One of two spellings of `object[key]` (`first` when absent): true for the second.
    Result<bool> either(const json& object, const char* key, const char* first, const char* second) const {
        const auto it = object.find(key);
        if (it == object.end()) return false;
        if (it->is_string() && (it->get<std::string>() == first || it->get<std::string>() == second))
            return it->get<std::string>() == second;
        return std::unexpected(
            error(fmt::format("motion.{}", key), fmt::format("expected \"{}\" or \"{}\"", first, second)));
    }

    // Spelled as sequence.json's "motion" (units, points_to, y_axis).
    Result<MotionConvention> motion(const json& root) const {
        MotionConvention m;
        const auto it = root.find("motion");
        if (it == root.end()) return m;
        if (!it->is_object()) return std::unexpected(error("motion", "expected an object (units, points_to, y_axis)"));
        if (auto ok = known_keys(*it, {"units", "points_to", "y_axis"}, "motion"); !ok)
            return std::unexpected(ok.error());
        auto uv = either(*it, "units", "pixels", "uv");
        auto current = either(*it, "points_to", "previous", "current");
        auto up = either(*it, "y_axis", "down", "up");
        for (const auto* r : {&uv, &current, &up})
            if (!*r) return std::unexpected(r->error());
        m.units = *uv ? MotionConvention::Units::uv : MotionConvention::Units::pixels;
        m.points_to = *current ? MotionConvention::PointsTo::current : MotionConvention::PointsTo::previous;
        m.y_axis = *up ? MotionConvention::YAxis::up : MotionConvention::YAxis::down;
        return m;
    }
};

} // namespace

const char* to_string(ResourceRole role) {
    switch (role) {
    case ResourceRole::current: return "current";
    case ResourceRole::history: return "history";
    case ResourceRole::output: return "output";
    case ResourceRole::motion: return "motion";
    case ResourceRole::depth: return "depth";
    case ResourceRole::sampler: return "sampler";
    }
    return "?";
}

const char* to_string(ValueRole role) {
    switch (role) {
    case ValueRole::current_weight: return "current_weight";
    case ValueRole::gamma: return "gamma";
    case ValueRole::jitter: return "jitter";
    case ValueRole::input_size: return "input_size";
    case ValueRole::output_size: return "output_size";
    case ValueRole::frame_index: return "frame_index";
    case ValueRole::reset: return "reset";
    case ValueRole::exposure: return "exposure";
    case ValueRole::sample_distance: return "sample_distance";
    }
    return "?";
}

MotionScale motion_scale(const MotionConvention& c, std::uint32_t width, std::uint32_t height) {
    MotionScale s;
    if (c.units == MotionConvention::Units::uv) s.x /= float(width), s.y /= float(height);
    if (c.y_axis == MotionConvention::YAxis::up) s.y = -s.y;
    if (c.points_to == MotionConvention::PointsTo::current) s.x = -s.x, s.y = -s.y;
    return s;
}

Result<ResolveBindings> parse_resolve_bindings(std::string_view text, const std::string& file) {
    const MapReader read{file};
    json root;
    try {
        root = json::parse(text);
    } catch (const json::exception& e) { // a syntax error, or a number too large for a double
        return fail(fmt::format("{}: not JSON: {}", file, shown_text(e.what(), 200)));
    }
    if (!root.is_object()) return fail(fmt::format("{}: expected a JSON object", file));
    if (auto ok = read.known_keys(root, {"format", "version", "resources", "push_constants", "uniforms", "motion"},
                                  "the map");
        !ok)
        return std::unexpected(ok.error());
    if (root.value("format", json()) != "kdop-resolve-bindings")
        return std::unexpected(read.error("format", "expected \"kdop-resolve-bindings\""));
    if (root.value("version", json()) != 1) return std::unexpected(read.error("version", "expected 1"));
    ResolveBindings map;
    map.file = file;
    auto resources = read.roles(root, "resources", kResourceRoles);
    if (!resources) return std::unexpected(resources.error());
    auto values = read.roles(root, "push_constants", kValueRoles);
    if (!values) return std::unexpected(values.error());
    auto uniforms = read.roles(root, "uniforms", kValueRoles);
    if (!uniforms) return std::unexpected(uniforms.error());
    // A value is written in one place: a role in both is refused as one given twice within either.
    for (const auto& [name, role] : *uniforms)
        for (const auto& [member, given] : *values)
            if (role == given)
                return std::unexpected(read.error(
                    fmt::format("uniforms.{}", shown_text(name, 60)),
                    fmt::format("the role {} is also given to push_constants.{}; kdop fills one resource or member "
                                "with each",
                                to_string(role), shown_text(member, 60))));
    auto motion = read.motion(root);
    if (!motion) return std::unexpected(motion.error());
    map.resources = std::move(*resources), map.push_constants = std::move(*values);
    map.uniforms = std::move(*uniforms), map.motion = *motion;
    return map;
}

Result<ResolveBindings> read_resolve_bindings(const std::filesystem::path& file) {
    auto text = read_input_file(file);
    if (!text) return std::unexpected(text.error());
    return parse_resolve_bindings(*text, file.string());
}

const DescriptorBinding* BoundResolve::find(ResourceRole role) const {
    for (const Resource& r : resources)
        if (r.role == role) return r.binding;
    return nullptr;
}

namespace {

// VkFormat values of the outputs kdop reads back.
constexpr std::uint32_t kRgba32f = 109, kRgba16f = 97;

// Why `b` cannot take `role`, or nothing where it can.
std::optional<std::string> type_mismatch(const DescriptorBinding& b, ResourceRole role) {
    switch (role) {
    case ResourceRole::output:
        if (b.type != DescriptorType::storage_image) return "a storage image (image2D, RWTexture2D)";
        if (b.format != kRgba32f && b.format != kRgba16f)
            return "a storage image of rgba32f or rgba16f, which hold what kdop measures";
        return std::nullopt;
    case ResourceRole::sampler:
        return b.type == DescriptorType::sampler ? std::nullopt
                                                 : std::optional<std::string>("a sampler (SamplerState)");
    default:
        return b.type == DescriptorType::combined_image_sampler || b.type == DescriptorType::sampled_image
                   ? std::nullopt
                   : std::optional<std::string>("a sampled image (sampler2D, texture2D, Texture2D)");
    }
}

} // namespace

Result<BoundResolve> bind(const ResolveBindings& map, const Variant& shader,
                          std::span<const UniformMember> uniform_members) {
    const std::span<const DescriptorBinding> bindings(shader.bindings, shader.binding_count);
    const std::span<const PushConstantMember> members(shader.push_constants, shader.push_constant_count);
    auto refused = [&](const std::string& what) {
        return fail(fmt::format("{}: {}: {}", map.file, shader.name, what));
    };
    BoundResolve bound;
    bound.motion = map.motion;
    for (const auto& [name, role] : map.resources) {
        const auto b = std::ranges::find_if(bindings, [&](const DescriptorBinding& d) { return name == d.name; });
        if (b == bindings.end()) {
            std::vector<std::string> has;
            for (const DescriptorBinding& d : bindings) has.emplace_back(d.name);
            return refused(fmt::format("resources.{}: the shader has no resource \"{}\" (it has {})",
                                       shown_text(name, 60), shown_text(name, 60), fmt::join(has, ", ")));
        }
        if (auto expected = type_mismatch(*b, role))
            return refused(fmt::format("resources.{}: the role {} takes {}, and \"{}\" (set {}, binding {}) is not one",
                                       shown_text(name, 60), to_string(role), *expected, b->name, b->set, b->binding));
        bound.resources.push_back({role, &*b});
    }
    // A uniform block's members each take a value role, and then the block is bound by them.
    for (const auto& [name, role] : map.uniforms) {
        const auto m = std::ranges::find_if(uniform_members,
                                            [&](const UniformMember& u) { return name == u.block + "." + u.name; });
        const auto b =
            m == uniform_members.end()
                ? bindings.end()
                : std::ranges::find_if(bindings, [&](const DescriptorBinding& d) { return m->block == d.name; });
        if (b == bindings.end())
            return refused(fmt::format("uniforms.{}: the shader has no uniform block member \"{}\" (named "
                                       "\"<block>.<member>\", the block as its resources are)",
                                       shown_text(name, 60), shown_text(name, 60)));
        if (m->size != value_size(role))
            return refused(fmt::format(
                "uniforms.{}: the role {} takes {} bytes ({}), and \"{}\" is {}", shown_text(name, 60), to_string(role),
                value_size(role), value_size(role) == 8 ? "a vec2" : "a float or uint", shown_text(name, 60), m->size));
        bound.uniforms.push_back({role, &*b, m->offset, m->size});
    }
    for (const UniformMember& u : uniform_members)
        if (std::ranges::none_of(map.uniforms,
                                 [&](const auto& given) { return given.first == u.block + "." + u.name; }))
            return refused(fmt::format("its uniform block member \"{}.{}\" has no role in the map's \"uniforms\", "
                                       "so kdop could not fill it",
                                       u.block, u.name));
    const auto is_uniform_block = [&](const DescriptorBinding& d) {
        return d.type == DescriptorType::uniform_buffer &&
               std::ranges::any_of(bound.uniforms, [&](const BoundResolve::Uniform& u) { return u.block == &d; });
    };
    for (const DescriptorBinding& d : bindings)
        if (!is_uniform_block(d) &&
            std::ranges::none_of(bound.resources, [&](const auto& r) { return r.binding == &d; }))
            return refused(fmt::format("its resource \"{}\" (set {}, binding {}) has no role in the map's "
                                       "\"resources\", so kdop could not bind it",
                                       d.name, d.set, d.binding));
    for (ResourceRole required : {ResourceRole::current, ResourceRole::history, ResourceRole::output})
        if (!bound.find(required))
            return refused(fmt::format("no resource has the role {}; a resolve reads the current frame and its "
                                       "history and writes its output",
                                       to_string(required)));
    for (const auto& [name, role] : map.push_constants) {
        const auto m = std::ranges::find_if(members, [&](const PushConstantMember& p) { return name == p.name; });
        if (m == members.end())
            return refused(fmt::format("push_constants.{}: the shader has no push-constant member \"{}\"",
                                       shown_text(name, 60), shown_text(name, 60)));
        if (m->size != value_size(role))
            return refused(fmt::format("push_constants.{}: the role {} takes {} bytes ({}), and \"{}\" is {}",
                                       shown_text(name, 60), to_string(role), value_size(role),
                                       value_size(role) == 8 ? "a vec2" : "a float or uint", m->name, m->size));
        bound.values.push_back({role, &*m});
    }
    for (const PushConstantMember& p : members)
        if (std::ranges::none_of(bound.values, [&](const auto& v) { return v.member == &p; }))
            return refused(fmt::format("its push-constant member \"{}\" has no role in the map's \"push_constants\", "
                                       "so kdop could not fill it",
                                       p.name));
    return bound;
}

} // namespace kdop
