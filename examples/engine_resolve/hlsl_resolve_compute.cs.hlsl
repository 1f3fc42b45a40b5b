// resolve_compute.comp as an Unreal- or Unity-style engine writes it in HLSL: the same resolve
// (reproject by the motion, clip to the 3x3 neighborhood's 22-DOP, blend) with HLSL's resources,
// Texture2D and SamplerState kept apart (the history's linear sampler is a binding of its own),
// the parameters in a constant buffer, the output in an RWTexture2D and the clip distances in an
// RWStructuredBuffer. kdop-gen compiles it with glslang's HLSL front end: each register's number is
// its binding and its space its set (register(t2) is binding 2 of set 0); the numbers are
// distinct because t0 and s0 would land on the same binding. [[vk::binding(b, s)]] says the same
// explicitly, as `history_sampler` shows.
#include "dop22-clip-n9.hlsl"

struct ResolveParameters
{
    float2 motion;        // screen motion in pixels of the whole frame (a camera pan)
    float current_weight; // share of this frame in the blend, e.g. 0.1
};

Texture2D<float4> current_texture : register(t0);            // this frame (jittered)
SamplerState nearest_sampler : register(s1);                 // for current_texture
Texture2D<float4> history_frame : register(t2);              // last frame's resolve
RWTexture2D<float4> resolved_frame : register(u3);           // this frame's resolve
[[vk::binding(4, 0)]] SamplerState history_sampler;          // linear, for history_frame
ConstantBuffer<ResolveParameters> parameters : register(b0, space1);
RWStructuredBuffer<float> clip_distances : register(u1, space1); // per pixel, row-major: |history - clipped history|

// At a texel's center a nearest sample is that texel, as texelFetch gives it in the GLSL resolve.
float3 current_at(int2 p, int2 size)
{
    const float2 uv = (float2(clamp(p, int2(0, 0), size - 1)) + 0.5) / float2(size);
    return current_texture.SampleLevel(nearest_sampler, uv, 0).rgb;
}

[numthreads(8, 8, 1)]
void main(uint3 id : SV_DispatchThreadID)
{
    uint width, height;
    current_texture.GetDimensions(width, height);
    const int2 size = int2(width, height);
    const int2 p = int2(id.xy);
    if (p.x >= size.x || p.y >= size.y) return;

    float3 neighborhood[9];
    for (int i = 0; i < 9; ++i) neighborhood[i] = current_at(p + int2(i % 3 - 1, i / 3 - 1), size);
    const float3 current = neighborhood[4];
    const float2 uv = (float2(p) + 0.5 - parameters.motion) / float2(size);
    const float3 history = history_frame.SampleLevel(history_sampler, uv, 0).rgb;
    const float3 clipped = kdop_dop22_clip_n9(current, history, neighborhood);
    resolved_frame[p] = float4(lerp(clipped, current, parameters.current_weight), 1.0);
    clip_distances[p.y * size.x + p.x] = distance(history, clipped);
}
