#version 450
// A TAAU resolve, as an engine that renders below the display size writes it: this frame's color
// and motion at the input size, the history and the output at the output size, and the frame's
// jitter in push constants. For each output pixel it takes the input sample nearest the pixel's
// center, clips the reprojected history to that sample's 3x3 neighborhood with kdop's
// dop22-clip-n9 (included at build time) and blends in the 3x3 filtered at the center. It is the
// upscaling path of kdop's own resolve (docs/taa.md, "Upscaling") with its defaults, written out.
// The variant: dop22-clip-n9 here, each variant measured under kdop taa --resolve.
#include "kdop_variant.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

layout(set = 0, binding = 0) uniform sampler2D current_frame; // this frame, input size (jittered)
layout(set = 0, binding = 1) uniform sampler2D motion_frame;  // input size: .xy, input pixels to where each sample was
layout(set = 0, binding = 2) uniform sampler2D history_frame; // output size: last frame's resolve
layout(set = 0, binding = 3, rgba32f) uniform writeonly image2D resolved_frame; // output size: this frame's

layout(push_constant) uniform UpscaleParameters
{
    vec2 jitter;          // input pixel i's sample lies at i + 0.5 + jitter (y down)
    float current_weight; // share of this frame in the blend, e.g. 0.1; 1 starts the history
} parameters;

// Lanczos-2 of a sample's distance d from the output pixel's center, in input pixels.
float lanczos2(vec2 d)
{
    const float x = length(d);
    if (x < 1e-5) return 1.0;
    if (x >= 2.0) return 0.0;
    const float pi_x = 3.14159265358979 * x;
    return 2.0 * sin(pi_x) * sin(0.5 * pi_x) / (pi_x * pi_x);
}

vec3 history_texel(ivec2 q, ivec2 last)
{
    return texelFetch(history_frame, clamp(q, ivec2(0), last), 0).rgb;
}

// The history at x (output pixels), bilinear and clamped to the edge. Written out rather than
// sampled so that it is the same on every device, as kdop's resolve, which this is checked
// against, does it; a linear sampler does the same to its filtering precision.
vec3 history_at(vec2 x, ivec2 last)
{
    const vec2 t = x - 0.5;
    const ivec2 i = ivec2(floor(t));
    const vec2 f = t - floor(t);
    return mix(mix(history_texel(i, last), history_texel(i + ivec2(1, 0), last), f.x),
               mix(history_texel(i + ivec2(0, 1), last), history_texel(i + ivec2(1, 1), last), f.x), f.y);
}

void main()
{
    const ivec2 in_size = textureSize(current_frame, 0);
    const ivec2 out_size = imageSize(resolved_frame);
    const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= out_size.x || p.y >= out_size.y) return;

    // The output pixel's center in input pixels, and the input sample nearest it.
    const vec2 scale = vec2(in_size) / vec2(out_size);
    const vec2 center = (vec2(p) + 0.5) * scale;
    const ivec2 nearest = clamp(ivec2(floor(center - parameters.jitter)), ivec2(0), in_size - 1);

    // The nearest sample's 3x3, which bounds the history, and this frame's color at the center:
    // the 3x3 filtered with Lanczos-2, clamped to the 3x3's range against the filter's ringing.
    vec3 neighborhood[9];
    vec3 sum = vec3(0.0), low = vec3(1e30), high = vec3(-1e30);
    float weights = 0.0;
    for (int i = 0; i < 9; ++i)
    {
        const ivec2 q = clamp(nearest + ivec2(i % 3 - 1, i / 3 - 1), ivec2(0), in_size - 1);
        neighborhood[i] = texelFetch(current_frame, q, 0).rgb;
        const float w = lanczos2(vec2(q) + 0.5 + parameters.jitter - center);
        sum += w * neighborhood[i];
        weights += w;
        low = min(low, neighborhood[i]);
        high = max(high, neighborhood[i]);
    }
    const vec3 current = clamp(weights > 1e-6 ? sum / weights : neighborhood[4], low, high);

    // Where this pixel was last frame: the nearest sample's motion, scaled to output pixels. Off
    // screen, or on the first frame, there is no history.
    const vec2 motion = texelFetch(motion_frame, nearest, 0).xy / scale;
    const vec2 previous = vec2(p) + 0.5 + motion;
    const bool off_screen = any(lessThan(previous, vec2(0.0))) || any(greaterThan(previous, vec2(out_size)));
    if (parameters.current_weight >= 1.0 || off_screen)
    {
        imageStore(resolved_frame, p, vec4(current, 1.0));
        return;
    }

    // The clip's `current` is the neighborhood's center, the nearest sample. The blend weighs this
    // frame by how near that sample fell to the center, in output pixels (1 on it), so a still
    // image converges to the jittered samples' average.
    const vec3 clipped = kdop_rectify(neighborhood[4], history_at(previous, out_size - 1), 1.0, neighborhood);
    const vec2 offset = (vec2(nearest) + 0.5 + parameters.jitter - center) / scale;
    const float weight = parameters.current_weight * exp(-2.0 * dot(offset, offset));
    imageStore(resolved_frame, p, vec4(clipped + weight * (current - clipped), 1.0));
}
