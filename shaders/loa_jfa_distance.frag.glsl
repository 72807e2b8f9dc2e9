#version 330 compatibility
// The last pass of osgLoA::DistanceField: per grid texel, the distance to the nearest seed the
// flooding found (loa_jfa_step.frag.glsl; 4 grid texels per RGBA32UI texel), in texels times
// loa_jfaDistanceScale (1, or the texel size for world units); +infinity where none was found.
uniform usampler2D loa_jfaSeeds;
uniform float loa_jfaDistanceScale;

layout(location = 0) out float loa_jfaDistance;

const uint LOA_JFA_NONE = 0xFFFFFFFFu;

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    uint s = texelFetch(loa_jfaSeeds, ivec2(p.x >> 2, p.y), 0)[p.x & 3];
    ivec2 e = ivec2(int(s & 0xFFFFu), int(s >> 16)) - p;
    loa_jfaDistance = s == LOA_JFA_NONE ? uintBitsToFloat(0x7F800000u) : sqrt(float(e.x * e.x + e.y * e.y)) * loa_jfaDistanceScale;
}
