#version 450
// A TAA resolve as an engine ported from HLSL writes it: the current frame as a separate texture
// and sampler, the history as a combined image sampler, the per-frame parameters in a uniform
// buffer, the output to a storage image, and how far each pixel's history was moved by the clip to
// a storage buffer (a debug view). The history is reprojected by the motion, clipped to the 3x3
// neighborhood's 22-DOP (kdop's dop22-clip-n9, included at build time) and blended.
#include "dop22-clip-n9.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

layout(set = 0, binding = 0) uniform texture2D current_texture;                 // this frame (jittered)
layout(set = 0, binding = 1) uniform sampler nearest_sampler;                   // for current_texture
layout(set = 0, binding = 2) uniform sampler2D history_frame;                   // last frame's resolve (linear)
layout(set = 0, binding = 3, rgba32f) uniform writeonly image2D resolved_frame; // this frame's resolve
layout(set = 1, binding = 0) uniform ResolveParameters
{
    vec2 motion;          // screen motion in pixels of the whole frame (a camera pan)
    float current_weight; // share of this frame in the blend, e.g. 0.1
} parameters;
layout(set = 1, binding = 1) buffer ClipDistances
{
    float clip_distance[]; // per pixel, row-major: |history - clipped history|
} clip_distances;

vec3 current_at(ivec2 p, ivec2 size)
{
    return texelFetch(sampler2D(current_texture, nearest_sampler), clamp(p, ivec2(0), size - 1), 0).rgb;
}

void main()
{
    const ivec2 size = textureSize(sampler2D(current_texture, nearest_sampler), 0);
    const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= size.x || p.y >= size.y) return;

    vec3 neighborhood[9];
    for (int i = 0; i < 9; ++i) neighborhood[i] = current_at(p + ivec2(i % 3 - 1, i / 3 - 1), size);
    const vec3 current = neighborhood[4];
    const vec2 uv = (vec2(p) + 0.5 - parameters.motion) / vec2(size);
    const vec3 history = texture(history_frame, uv).rgb;
    const vec3 clipped = kdop_dop22_clip_n9(current, history, neighborhood);
    imageStore(resolved_frame, p, vec4(mix(clipped, current, parameters.current_weight), 1.0));
    clip_distances.clip_distance[p.y * size.x + p.x] = distance(history, clipped);
}
