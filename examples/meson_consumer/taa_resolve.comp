#version 450
// A TAA resolve as a Meson project keeps it: this frame and the history in, the history clipped to
// the 3x3 neighborhood's 22-DOP (kdop's dop22-clip-n9, included at build time) and blended out.
#include "dop22-clip-n9.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform sampler2D current_frame;
layout(set = 0, binding = 1) uniform sampler2D history_frame;
layout(set = 0, binding = 2, rgba16f) uniform writeonly image2D resolved_frame;
layout(push_constant) uniform Blend
{
    float current_weight;
} blend;

void main()
{
    const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    const ivec2 size = textureSize(current_frame, 0);
    if (p.x >= size.x || p.y >= size.y) return;
    vec3 neighborhood[9];
    for (int i = 0; i < 9; ++i)
        neighborhood[i] = texelFetch(current_frame, clamp(p + ivec2(i % 3 - 1, i / 3 - 1), ivec2(0), size - 1), 0).rgb;
    const vec3 history = texelFetch(history_frame, p, 0).rgb;
    const vec3 clipped = kdop_dop22_clip_n9(neighborhood[4], history, neighborhood);
    imageStore(resolved_frame, p, vec4(mix(clipped, neighborhood[4], blend.current_weight), 1.0));
}
