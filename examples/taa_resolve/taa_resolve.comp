#version 450
// A TAA resolve written by a renderer team, with kdop's clip compiled in at build time:
//   kdop_add_variants(<target> SETS dop22 MODES clip NEIGHBORHOODS n9 SHADERS taa_resolve.comp)
// embeds it, optimized and reflected, next to the variants, as the registry entry "taa_resolve".
//
// Per pixel: reproject last frame's resolve with the camera's motion, clip it to the dop22 k-DOP of
// this frame's 3x3 neighborhood, and blend this frame in. (A renderer with moving objects reads a
// motion-vector texture instead of one motion for the frame.)
#include "dop22-clip-n9.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

layout(set = 0, binding = 0) uniform sampler2D current_frame;               // this frame (jittered)
layout(set = 0, binding = 1) uniform sampler2D history_frame;               // last frame's resolve
layout(set = 0, binding = 2, rgba32f) uniform writeonly image2D rectified_history; // this frame's resolve

layout(push_constant) uniform Parameters
{
    vec2 motion;          // pixels the scene moved since last frame
    float current_weight; // share of this frame in the blend, e.g. 0.1
} parameters;

vec3 current_at(ivec2 p, ivec2 last)
{
    return texelFetch(current_frame, clamp(p, ivec2(0), last), 0).rgb;
}

void main()
{
    const ivec2 size = textureSize(current_frame, 0);
    const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= size.x || p.y >= size.y)
        return;
    const ivec2 last = size - 1;

    vec3 neighborhood[9];
    for (int y = -1; y <= 1; ++y)
        for (int x = -1; x <= 1; ++x)
            neighborhood[(y + 1) * 3 + (x + 1)] = current_at(p + ivec2(x, y), last);
    const vec3 current = neighborhood[4];

    // Where this pixel was last frame; the history's sampler filters and clamps to the edge.
    const vec2 uv = (vec2(p) + 0.5 - parameters.motion) / vec2(size);
    const vec3 history = textureLod(history_frame, uv, 0.0).rgb;

    const vec3 clipped = kdop_dop22_clip_n9(current, history, neighborhood);
    imageStore(rectified_history, p, vec4(mix(clipped, current, parameters.current_weight), 1.0));
}
