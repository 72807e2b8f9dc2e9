#version 330 compatibility
// One jump-flooding pass of step loa_jfaStep (osgLoA::DistanceField; Rong & Tan 2006).
//
// Every grid texel holds its nearest seed so far, packed as x | y << 16 (0xFFFFFFFF: none).
// Four texels share one RGBA32UI texel: grid texel x of row y is component x % 4 of texel
// (x / 4, y), so a fragment floods 4 grid texels with 9 fetches instead of 36 (on llvmpipe 1.85x
// less CPU time than one R32UI texel per fragment; docs/distance-field.md).
//
// The logic, per grid texel p, as DistanceField::computeJFA has it on the CPU (keep them equal):
// look at p + (dx, dy) * step for dy = -1..1 (outer), dx = -1..1 (inner); skip those outside the
// grid and those without seed; keep the seed with the smallest integer squared distance to p;
// on a tie the first in that order wins. Components of texels past the grid's width hold none.
uniform usampler2D loa_jfaSeeds;
uniform int loa_jfaStep;
uniform int loa_jfaWidth; // grid texels along x

layout(location = 0) out uvec4 loa_jfaNearest;

const uint LOA_JFA_NONE = 0xFFFFFFFFu;

// The packed texel q, or none when q lies outside the texture.
uvec4 loa_jfaFetch(ivec2 q, ivec2 size)
{
    uvec4 v = texelFetch(loa_jfaSeeds, clamp(q, ivec2(0), size - 1), 0);
    bool inside = all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, size));
    return inside ? v : uvec4(LOA_JFA_NONE);
}

// Keeps, per component, candidate s where it is strictly nearer than the best so far.
void loa_jfaConsider(uvec4 s, ivec4 px, int py, inout uvec4 best, inout ivec4 bestD2)
{
    ivec4 ex = ivec4(s & 0xFFFFu) - px;
    ivec4 ey = ivec4(s >> 16) - py;
    // none: the largest int, which never wins (bestD2 starts there too)
    ivec4 d2 = max(ex * ex + ey * ey, ivec4(equal(s, uvec4(LOA_JFA_NONE))) * 0x7FFFFFFF);
    uvec4 nearer = uvec4(lessThan(d2, bestD2));
    best += (s - best) * nearer; // select without branches (GLSL 3.30 has no integer mix)
    bestD2 = min(bestD2, d2);
}

void main()
{
    ivec2 pack = ivec2(gl_FragCoord.xy);
    ivec2 size = textureSize(loa_jfaSeeds, 0);
    int k = loa_jfaStep;
    ivec4 px = ivec4(pack.x * 4) + ivec4(0, 1, 2, 3);
    // Steps of 4 and more move whole packed texels; steps 1 and 2 shift within neighbours.
    int kp = k >= 4 ? k / 4 : 1;
    uvec4 best = uvec4(LOA_JFA_NONE);
    ivec4 bestD2 = ivec4(0x7FFFFFFF);
    for (int dy = -1; dy <= 1; ++dy)
    {
        int y = pack.y + dy * k;
        uvec4 a = loa_jfaFetch(ivec2(pack.x - kp, y), size);
        uvec4 b = loa_jfaFetch(ivec2(pack.x, y), size);
        uvec4 c = loa_jfaFetch(ivec2(pack.x + kp, y), size);
        uvec4 left = k == 1 ? uvec4(a.w, b.xyz) : k == 2 ? uvec4(a.zw, b.xy) : a;
        uvec4 right = k == 1 ? uvec4(b.yzw, c.x) : k == 2 ? uvec4(b.zw, c.xy) : c;
        loa_jfaConsider(left, px, pack.y, best, bestD2);
        loa_jfaConsider(b, px, pack.y, best, bestD2);
        loa_jfaConsider(right, px, pack.y, best, bestD2);
    }
    // Components past the grid's width hold none.
    loa_jfaNearest = best | uvec4(greaterThanEqual(px, ivec4(loa_jfaWidth))) * LOA_JFA_NONE;
}
