#version 450
// The same TAA resolve as a full-screen fragment pass (fullscreen.vert), as many engines run it: the
// current frame and the history as one array of two combined image samplers, the motion in a
// uniform buffer, the blend weight as a fragment-stage push constant, the resolve written to color
// attachment 0.
#include "dop22-clip-n9.glsl"

layout(set = 0, binding = 0) uniform sampler2D frames[2]; // [0] this frame (nearest), [1] the history (linear)
layout(set = 0, binding = 1) uniform ResolveParameters
{
    vec2 motion; // screen motion in pixels of the whole frame
} parameters;
layout(push_constant) uniform Blend
{
    float current_weight;
} blend;

layout(location = 0) out vec4 resolved;

void main()
{
    const ivec2 size = textureSize(frames[0], 0);
    const ivec2 p = ivec2(gl_FragCoord.xy);
    vec3 neighborhood[9];
    for (int i = 0; i < 9; ++i)
        neighborhood[i] = texelFetch(frames[0], clamp(p + ivec2(i % 3 - 1, i / 3 - 1), ivec2(0), size - 1), 0).rgb;
    const vec3 current = neighborhood[4];
    const vec3 history = texture(frames[1], (gl_FragCoord.xy - parameters.motion) / vec2(size)).rgb;
    const vec3 clipped = kdop_dop22_clip_n9(current, history, neighborhood);
    resolved = vec4(mix(clipped, current, blend.current_weight), 1.0);
}
