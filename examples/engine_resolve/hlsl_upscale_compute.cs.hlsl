// upscale_compute.comp as an Unreal- or Unity-style engine writes it in HLSL: the same TAAU resolve
// (the nearest input sample's 3x3 clips the reprojected history with kdop's dop22-clip-n9, the 3x3
// filtered at the output pixel's center blends in) with HLSL's resources: Texture2D read with Load,
// so no sampler, an RWTexture2D for the output and the parameters in push constants.
// The variant: dop22-clip-n9 here, each variant measured under kdop taa --resolve.
#include "kdop_variant.hlsl"

struct UpscaleParameters
{
    float2 jitter;        // input pixel i's sample lies at i + 0.5 + jitter (y down)
    float current_weight; // share of this frame in the blend, e.g. 0.1; 1 starts the history
};

Texture2D<float4> current_frame : register(t0);    // this frame, input size (jittered)
Texture2D<float4> motion_frame : register(t1);     // input size: .xy, input pixels to where each sample was
Texture2D<float4> history_frame : register(t2);    // output size: last frame's resolve
RWTexture2D<float4> resolved_frame : register(u3); // output size: this frame's
[[vk::push_constant]] ConstantBuffer<UpscaleParameters> parameters;

// Lanczos-2 of a sample's distance d from the output pixel's center, in input pixels.
float lanczos2(float2 d)
{
    const float x = length(d);
    if (x < 1e-5) return 1.0;
    if (x >= 2.0) return 0.0;
    const float pi_x = 3.14159265358979 * x;
    return 2.0 * sin(pi_x) * sin(0.5 * pi_x) / (pi_x * pi_x);
}

float3 history_texel(int2 q, int2 last)
{
    return history_frame.Load(int3(clamp(q, int2(0, 0), last), 0)).rgb;
}

// The history at x (output pixels), bilinear and clamped to the edge, written out as in the GLSL.
float3 history_at(float2 x, int2 last)
{
    const float2 t = x - 0.5;
    const int2 i = int2(floor(t));
    const float2 f = t - floor(t);
    return lerp(lerp(history_texel(i, last), history_texel(i + int2(1, 0), last), f.x),
                lerp(history_texel(i + int2(0, 1), last), history_texel(i + int2(1, 1), last), f.x), f.y);
}

[numthreads(8, 8, 1)]
void main(uint3 id : SV_DispatchThreadID)
{
    uint in_width, in_height, out_width, out_height;
    current_frame.GetDimensions(in_width, in_height);
    resolved_frame.GetDimensions(out_width, out_height);
    const int2 in_size = int2(in_width, in_height);
    const int2 out_size = int2(out_width, out_height);
    const int2 p = int2(id.xy);
    if (p.x >= out_size.x || p.y >= out_size.y) return;

    // The output pixel's center in input pixels, and the input sample nearest it.
    const float2 scale = float2(in_size) / float2(out_size);
    const float2 center = (float2(p) + 0.5) * scale;
    const int2 nearest = clamp(int2(floor(center - parameters.jitter)), int2(0, 0), in_size - 1);

    // The nearest sample's 3x3, which bounds the history, and this frame's color at the center.
    float3 neighborhood[9];
    float3 sum = 0.0, low = 1e30, high = -1e30;
    float weights = 0.0;
    for (int i = 0; i < 9; ++i)
    {
        const int2 q = clamp(nearest + int2(i % 3 - 1, i / 3 - 1), int2(0, 0), in_size - 1);
        neighborhood[i] = current_frame.Load(int3(q, 0)).rgb;
        const float w = lanczos2(float2(q) + 0.5 + parameters.jitter - center);
        sum += w * neighborhood[i];
        weights += w;
        low = min(low, neighborhood[i]);
        high = max(high, neighborhood[i]);
    }
    const float3 current = clamp(weights > 1e-6 ? sum / weights : neighborhood[4], low, high);

    // Where this pixel was last frame; off screen, or on the first frame, there is no history.
    const float2 motion = motion_frame.Load(int3(nearest, 0)).xy / scale;
    const float2 previous = float2(p) + 0.5 + motion;
    if (parameters.current_weight >= 1.0 || any(previous < 0.0) || any(previous > float2(out_size)))
    {
        resolved_frame[p] = float4(current, 1.0);
        return;
    }

    // Clipped toward the nearest sample; this frame weighed by how near that sample fell.
    const float3 clipped = kdop_rectify(neighborhood[4], history_at(previous, out_size - 1), 1.0, neighborhood);
    const float2 offset = (float2(nearest) + 0.5 + parameters.jitter - center) / scale;
    const float weight = parameters.current_weight * exp(-2.0 * dot(offset, offset));
    resolved_frame[p] = float4(clipped + weight * (current - clipped), 1.0);
}
