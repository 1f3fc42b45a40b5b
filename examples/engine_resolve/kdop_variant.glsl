// The variant this engine ships, behind the one name kdop measures a resolve by: the upscale
// resolves include "kdop_variant.glsl" and clip with kdop_rectify(). Built here, it is
// dop22-clip-n9; under `kdop taa --resolve upscale_compute.comp`, kdop gives its own
// "kdop_variant.glsl" instead, one for each variant it measures, and the same resolve measures
// them all (docs/taa.md, "Your own resolve").
#include "dop22-clip-n9.glsl"

#define KDOP_NEIGHBORS 9
vec3 kdop_rectify(vec3 current, vec3 history, float gamma, vec3 neighborhood[KDOP_NEIGHBORS])
{
    return kdop_dop22_clip_n9(current, history, neighborhood); // a clip: no gamma
}
