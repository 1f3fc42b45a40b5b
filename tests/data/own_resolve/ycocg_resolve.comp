#version 450
// A resolve that differs from kdop's where it matters, as many engines write theirs: the history
// is clipped and blended in YCoCg, the blend weighted by luminance (Karis 2014: each side divided
// by 1 + its luma, so a bright outlier does not dominate), the textures separate from their one
// sampler, the motion in UV units, and the history started by a reset flag. kdop's tests run it
// through kdop taa --resolve's path and check every output against a CPU restatement.
#include "kdop_variant.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

layout(set = 0, binding = 0) uniform texture2D scene_color;
layout(set = 0, binding = 1) uniform texture2D scene_velocity; // UV to the previous position, y down
layout(set = 0, binding = 2) uniform texture2D accumulated;
layout(set = 0, binding = 3) uniform sampler linear_clamp;
layout(set = 0, binding = 4, rgba32f) uniform writeonly image2D resolved;

layout(push_constant) uniform Constants
{
    uint reset;        // 1: no history (the first frame, a camera cut)
    float blend;       // this frame's share before the luminance weights
    float variance_gamma;
} constants;

vec3 to_ycocg(vec3 c)
{
    return vec3(0.25 * c.r + 0.5 * c.g + 0.25 * c.b, 0.5 * c.r - 0.5 * c.b, -0.25 * c.r + 0.5 * c.g - 0.25 * c.b);
}

vec3 to_rgb(vec3 y)
{
    return vec3(y.x + y.y - y.z, y.x + y.z, y.x - y.y - y.z);
}

void main()
{
    const ivec2 size = textureSize(sampler2D(scene_color, linear_clamp), 0);
    const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= size.x || p.y >= size.y) return;

    vec3 neighborhood[KDOP_NEIGHBORS];
#if KDOP_NEIGHBORS == 9
    for (int i = 0; i < 9; ++i)
    {
        const ivec2 q = clamp(p + ivec2(i % 3 - 1, i / 3 - 1), ivec2(0), size - 1);
        neighborhood[i] = to_ycocg(texelFetch(sampler2D(scene_color, linear_clamp), q, 0).rgb);
    }
    const vec3 current = neighborhood[4];
#else
    const ivec2 plus[5] = ivec2[](ivec2(0, -1), ivec2(-1, 0), ivec2(0, 0), ivec2(1, 0), ivec2(0, 1));
    for (int i = 0; i < 5; ++i)
        neighborhood[i] = to_ycocg(texelFetch(sampler2D(scene_color, linear_clamp), clamp(p + plus[i], ivec2(0), size - 1), 0).rgb);
    const vec3 current = neighborhood[2];
#endif

    const vec2 uv = (vec2(p) + 0.5) / vec2(size);
    const vec2 previous = uv + texelFetch(sampler2D(scene_velocity, linear_clamp), p, 0).xy;
    if (constants.reset != 0u || any(lessThan(previous, vec2(0.0))) || any(greaterThan(previous, vec2(1.0))))
    {
        imageStore(resolved, p, vec4(to_rgb(current), 1.0));
        return;
    }
    const vec3 history = to_ycocg(textureLod(sampler2D(accumulated, linear_clamp), previous, 0.0).rgb);
    const vec3 clipped = kdop_rectify(current, history, constants.variance_gamma, neighborhood);
    const float w_current = constants.blend / (1.0 + current.x);
    const float w_history = (1.0 - constants.blend) / (1.0 + clipped.x);
    imageStore(resolved, p, vec4(to_rgb((w_current * current + w_history * clipped) / (w_current + w_history)), 1.0));
}
