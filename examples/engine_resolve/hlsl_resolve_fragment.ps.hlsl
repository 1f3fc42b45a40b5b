// resolve_fragment.frag as an HLSL pixel shader: the current frame and the history as an array of
// two textures with an array of two samplers beside it ([0] nearest, [1] linear), the motion in a
// constant buffer, the blend weight as a push constant ([[vk::push_constant]]), the resolve
// written to render target 0.
#include "dop22-clip-n9.hlsl"

struct ResolveParameters
{
    float2 motion; // screen motion in pixels of the whole frame
};
struct Blend
{
    float current_weight;
};

Texture2D<float4> frames[2] : register(t0);       // bindings 0: [0] this frame, [1] the history
ConstantBuffer<ResolveParameters> parameters : register(b1);
SamplerState frame_samplers[2] : register(s2);    // binding 2: [0] nearest, [1] linear
[[vk::push_constant]] ConstantBuffer<Blend> blend;

float4 main(float4 position : SV_Position) : SV_Target0
{
    uint width, height;
    frames[0].GetDimensions(width, height);
    const int2 size = int2(width, height);
    const int2 p = int2(position.xy);
    float3 neighborhood[9];
    for (int i = 0; i < 9; ++i)
        neighborhood[i] = frames[0].Load(int3(clamp(p + int2(i % 3 - 1, i / 3 - 1), int2(0, 0), size - 1), 0)).rgb;
    const float3 current = neighborhood[4];
    const float3 history = frames[1].SampleLevel(frame_samplers[1], (position.xy - parameters.motion) / float2(size), 0).rgb;
    const float3 clipped = kdop_dop22_clip_n9(current, history, neighborhood);
    return float4(lerp(clipped, current, blend.current_weight), 1.0);
}
