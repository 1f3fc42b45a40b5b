#include "testbed/testbed_renderer.h"

#include "generator/glsl_compiler.h"
#include "generator/runnable_variant.h"
#include "generator/shader_reflection.h"
#include "generator/spirv_tools.h"
#include "testbed/camera.h"

#include <fmt/format.h>

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include <span>
#include <vector>

namespace kdop {
namespace {

// The uniform block both stages read (std140: three matrices, then three vec4).
struct FrameUniforms {
    glm::mat4 jittered, current, previous; // world to clip: this frame's with jitter and without, the earlier one's
    glm::vec4 eye;                         // xyz: the camera
    glm::vec4 sun;                         // xyz: toward the sun; w: ambient
    glm::vec4 image;                       // x, y: width, height; z: texture repeats per world unit
};
static_assert(sizeof(FrameUniforms) == 240);

constexpr const char* kBlock = R"(layout(std140, set = 0, binding = 0) uniform Frame {
    mat4 jittered, current, previous;
    vec4 eye, sun, image;
} frame;
)";

constexpr const char* kVertexMain = R"(
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 previous_position;
layout(location = 2) in vec3 normal;
layout(location = 3) in vec4 surface; // albedo, textured
layout(location = 0) out vec4 current_clip;
layout(location = 1) out vec4 previous_clip;
layout(location = 2) out vec3 world_position;
layout(location = 3) out vec3 world_normal;
layout(location = 4) out vec4 albedo;

void main() {
    gl_Position = frame.jittered * vec4(position, 1.0);
    current_clip = frame.current * vec4(position, 1.0);
    previous_clip = frame.previous * vec4(previous_position, 1.0);
    world_position = position;
    world_normal = normal;
    albedo = surface;
}
)";

constexpr const char* kFragmentMain = R"(
layout(set = 0, binding = 1) uniform sampler2DArray ground;
layout(location = 0) in vec4 current_clip;
layout(location = 1) in vec4 previous_clip;
layout(location = 2) in vec3 world_position;
layout(location = 3) in vec3 world_normal;
layout(location = 4) in vec4 albedo;
layout(location = 0) out vec4 color;
layout(location = 1) out vec2 motion;

// Clip space to pixels, y down, as the framebuffer's rows.
vec2 pixel(vec4 clip) { return (clip.xy / clip.w * 0.5 + 0.5) * frame.image.xy; }

void main() {
    vec3 n = normalize(world_normal);
    if (dot(n, frame.eye.xyz - world_position) < 0.0) n = -n; // two-sided: lit on the side seen
    vec3 base = albedo.rgb;
    if (albedo.a > 0.5) base *= texture(ground, vec3(world_position.xz * frame.image.z, 0.0)).rgb;
    float light = frame.sun.w + (1.0 - frame.sun.w) * max(dot(n, frame.sun.xyz), 0.0);
    color = vec4(base * light, 1.0);
    // Both positions unjittered: the motion of the surface, whatever the jitter.
    motion = pixel(previous_clip) - pixel(current_clip);
}
)";

// A stage as glslang compiles it (validated, not optimized), with what it reflects: the registry
// entry the raster pass builds its pipeline and descriptor set from.
Result<std::unique_ptr<RunnableVariant>> build(const std::string& source, const char* name, ShaderStage stage) {
    auto spirv = compile_glsl(source, name, stage);
    if (!spirv) return std::unexpected(spirv.error());
    if (auto ok = validate_spirv(*spirv, source, name, "glslang output"); !ok) return std::unexpected(ok.error());
    auto interface = reflect_interface(*spirv);
    if (!interface) return std::unexpected(interface.error());
    BuiltVariant built;
    built.spec.mode = Mode::shader;
    built.name = name;
    built.spirv = std::move(*spirv);
    built.interface = std::move(*interface);
    return std::make_unique<RunnableVariant>(std::move(built));
}

// The vertices the pipeline takes: each vertex's position now and at the earlier instant.
std::vector<float> gpu_vertices(const Mesh& now, const Mesh& before) {
    std::vector<float> out;
    out.reserve(now.size() * 13);
    for (std::size_t i = 0; i < now.size(); ++i) {
        const MeshVertex &v = now[i], &p = before[i];
        out.insert(out.end(), {v.position.x, v.position.y, v.position.z, p.position.x, p.position.y, p.position.z,
                               v.normal.x, v.normal.y, v.normal.z, v.albedo.r, v.albedo.g, v.albedo.b, v.textured});
    }
    return out;
}

std::span<const std::byte> bytes_of(const std::vector<float>& v) { return std::as_bytes(std::span(v)); }

} // namespace

Result<std::unique_ptr<TestbedRenderer>> TestbedRenderer::create(const Context& context,
                                                                 std::shared_ptr<const Scene3d> scene,
                                                                 std::uint32_t width, std::uint32_t height) {
    const std::string header = std::string("#version 450\n") + kBlock;
    auto vertex = build(header + kVertexMain, "testbed.vert", ShaderStage::vertex);
    if (!vertex) return std::unexpected(vertex.error());
    auto fragment = build(header + kFragmentMain, "testbed.frag", ShaderStage::fragment);
    if (!fragment) return std::unexpected(fragment.error());
    RasterPipeline pipeline{
        &(*vertex)->variant(), &(*fragment)->variant(), {3, 3, 3, 4}, sizeof(FrameUniforms), scene->sky};
    auto pass = RasterPass::create(context, width, height, pipeline, scene->texture);
    if (!pass) return std::unexpected(pass.error());
    std::unique_ptr<TestbedRenderer> r(new TestbedRenderer);
    r->scene_ = std::move(scene);
    r->width_ = width;
    r->height_ = height;
    r->pass_ = std::move(*pass);
    if (auto ok = r->pass_->set_vertices(0, bytes_of(gpu_vertices(r->scene_->still, r->scene_->still))); !ok)
        return std::unexpected(ok.error());
    return r;
}

Result<std::vector<std::byte>> TestbedRenderer::prepare(double time, const Camera3d& camera, double previous_time,
                                                        const Camera3d& previous_camera, glm::vec2 jitter) {
    if (scene_->moving) {
        const Mesh now = scene_->moving(time), before = scene_->moving(previous_time);
        if (now.size() != before.size())
            return fail(fmt::format("{}: the moving mesh has {} vertices at time {} and {} at {}", scene_->name,
                                    now.size(), time, before.size(), previous_time));
        if (auto ok = pass_->set_vertices(1, bytes_of(gpu_vertices(now, before))); !ok)
            return std::unexpected(ok.error());
    }
    FrameUniforms u;
    u.current = view_projection(camera, width_, height_);
    u.jittered = jittered(u.current, jitter, width_, height_);
    u.previous = view_projection(previous_camera, width_, height_);
    u.eye = glm::vec4(camera.eye, 1);
    u.sun = glm::vec4(scene_->sun, scene_->ambient);
    u.image = glm::vec4(float(width_), float(height_), 1.0f / scene_->texture_period, 0);
    const auto bytes = std::as_bytes(std::span(&u, 1));
    return std::vector<std::byte>(bytes.begin(), bytes.end());
}

Result<RasterImages> TestbedRenderer::draw(double time, const Camera3d& camera, double previous_time,
                                           const Camera3d& previous_camera, glm::vec2 jitter) {
    auto uniforms = prepare(time, camera, previous_time, previous_camera, jitter);
    if (!uniforms) return std::unexpected(uniforms.error());
    return pass_->draw(*uniforms);
}

Result<void> TestbedRenderer::draw_into(double time, const Camera3d& camera, double previous_time,
                                        const Camera3d& previous_camera, glm::vec2 jitter, const RasterTargets& targets,
                                        Image* color_back) {
    auto uniforms = prepare(time, camera, previous_time, previous_camera, jitter);
    if (!uniforms) return std::unexpected(uniforms.error());
    return pass_->draw_into(*uniforms, targets, color_back);
}

} // namespace kdop
