// The variant this engine ships, behind the one name kdop measures a resolve by: the upscale
// resolves include "kdop_variant.hlsl" and clip with kdop_rectify(). Built here, it is
// dop22-clip-n9; under `kdop taa --resolve hlsl_upscale_compute.cs.hlsl`, kdop gives its own
// "kdop_variant.hlsl" instead, one for each variant it measures (docs/taa.md, "Your own resolve").
#include "dop22-clip-n9.hlsl"

#define KDOP_NEIGHBORS 9
float3 kdop_rectify(float3 current, float3 history, float gamma, float3 neighborhood[KDOP_NEIGHBORS])
{
    return kdop_dop22_clip_n9(current, history, neighborhood); // a clip: no gamma
}
