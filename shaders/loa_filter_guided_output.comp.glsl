#version 430
// The guided filter's output (osgLoA::GuidedFilter): q_c = mean(a_c) . I + mean(b_c) with I from
// input 0 and the window means of (a_c, b_c) for c = r, g, b from inputs 1..3; alpha passes
// through.
vec4 loa_fetch0(ivec2 p);
vec4 loa_fetch1(ivec2 p);
vec4 loa_fetch2(ivec2 p);
vec4 loa_fetch3(ivec2 p);

vec4 loa_filterTexel(ivec2 p)
{
    vec4 c = loa_fetch0(p);
    vec4 r = loa_fetch1(p), g = loa_fetch2(p), b = loa_fetch3(p);
    return vec4(dot(r.xyz, c.rgb) + r.w, dot(g.xyz, c.rgb) + g.w, dot(b.xyz, c.rgb) + b.w, c.a);
}
