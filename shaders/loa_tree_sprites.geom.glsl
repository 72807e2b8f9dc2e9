#version 450 compatibility
// Graphic style "trees" (paper 004 §3.2.3, Figure 8C, after Deussen & Strothotte 2000;
// osgLoA::TreeSilhouettes): tree crowns drawn as point sprites. Each triangle of a crown
// (drawables marked loa_treeCrown: TreeSilhouettes::markCrowns) becomes round leaf sprites facing
// the viewer, at points of the triangle fixed in the world:
//  - their number is the triangle's area times loa_trees_density, rounded up or down by a hash of
//    the triangle's corners (so the expected count is exact and the choice stable), at most
//    LOA_TREE_MAX_SPRITES;
//  - their barycentric positions follow the R2 low-discrepancy sequence from a hashed start;
//  - their radius is loa_trees_leafRadius world units, at least loa_trees_minPixels pixels (far
//    trees keep leaves of a few pixels, as Deussen & Strothotte enlarge the primitives of distant
//    trees);
//  - each sprite is flat, at the depth of its point: where sprites in front overlap sprites
//    behind, the depth steps, and the compositor's depth-discontinuity edges (relative to the
//    distance, loa_edgeThresholds) draw the outlines inside the crown that Deussen & Strothotte get
//    by thresholding depth differences. The threshold grows with distance, so far crowns keep
//    their silhouette only.
// The sprite's attributes are those of its point; its G-buffer normal faces the viewer (no normal
// edges between leaves); the crown's normal goes to the fragment stage in loa_texCoord1 (view x,
// y) for shading, the position in the sprite in loa_texCoord2 ([-1, 1]^2). Every other triangle
// passes through unchanged. CPU twin: TreeSilhouettes::spriteCount, spriteBarycentric.
#ifndef LOA_TREE_MAX_SPRITES
#define LOA_TREE_MAX_SPRITES 8
#endif
layout(triangles) in;
layout(triangle_strip, max_vertices = 32) out; // 4 x LOA_TREE_MAX_SPRITES

#pragma include "loa_geometry_stage.glsl"


uniform bool loa_treeCrown = false;
uniform float loa_trees_leafRadius = 0.6;
uniform float loa_trees_density = 2.0;
uniform float loa_trees_minPixels = 2.0;
uniform float loa_viewportHeight = 1080.0;

uint loa_trees_pcg(uint x)
{
    x = x * 747796405u + 2891336453u;
    uint w = ((x >> ((x >> 28u) + 4u)) ^ x) * 277803737u;
    return (w >> 22u) ^ w;
}

// A hash of the triangle's corners (scene coordinates in centimetres), order-independent.
uint loa_trees_triangleHash()
{
    uint h = 0u;
    for (int i = 0; i < 3; ++i)
    {
        ivec3 c = ivec3(round(loa_vsScenePosition[i] * 100.0));
        h += loa_trees_pcg(uint(c.x) * 73856093u ^ loa_trees_pcg(uint(c.y) * 19349663u ^ loa_trees_pcg(uint(c.z) * 83492791u)));
    }
    return loa_trees_pcg(h);
}

float loa_trees_unit(uint h)
{
    return float(h >> 8u) / 16777216.0;
}

void loa_trees_passThrough()
{
    for (int i = 0; i < 3; ++i)
    {
        loa_copyCorner(i);
        gl_Position = gl_in[i].gl_Position;
        EmitVertex();
    }
    EndPrimitive();
}

void main()
{
    if (!loa_treeCrown)
    {
        loa_trees_passThrough();
        return;
    }
    vec3 s0 = loa_vsScenePosition[0], s1 = loa_vsScenePosition[1], s2 = loa_vsScenePosition[2];
    float area = 0.5 * length(cross(s1 - s0, s2 - s0));
    uint h = loa_trees_triangleHash();
    float expected = area * loa_trees_density;
    int n = min(int(floor(expected + loa_trees_unit(h))), LOA_TREE_MAX_SPRITES);
    float u0 = loa_trees_unit(loa_trees_pcg(h ^ 0x9e3779b9u)), v0 = loa_trees_unit(loa_trees_pcg(h ^ 0x7f4a7c15u));
    // Pixels per world unit at view depth 1: the projection's y scale times half the viewport.
    float pixelsAtUnitDepth = gl_ProjectionMatrix[1][1] * 0.5 * loa_viewportHeight;
    bool ortho = gl_ProjectionMatrix[3][3] == 1.0;
    for (int k = 0; k < n; ++k)
    {
        // R2 sequence (plastic number), folded into the triangle.
        float u = fract(u0 + 0.7548776662 * float(k + 1)), v = fract(v0 + 0.5698402910 * float(k + 1));
        if (u + v > 1.0)
        {
            u = 1.0 - u;
            v = 1.0 - v;
        }
        vec3 b = vec3(1.0 - u - v, u, v);
        vec3 scene = b.x * s0 + b.y * s1 + b.z * s2;
        vec3 view = b.x * loa_vsViewPosition[0] + b.y * loa_vsViewPosition[1] + b.z * loa_vsViewPosition[2];
        vec3 normal = normalize(b.x * loa_vsViewNormal[0] + b.y * loa_vsViewNormal[1] + b.z * loa_vsViewNormal[2]);
        vec2 tc = b.x * loa_vsTexCoord[0] + b.y * loa_vsTexCoord[1] + b.z * loa_vsTexCoord[2];
        vec4 color = b.x * loa_vsColor[0] + b.y * loa_vsColor[1] + b.z * loa_vsColor[2];
        float depth = ortho ? 1.0 : max(-view.z, 1.0e-4);
        float radius = max(loa_trees_leafRadius, loa_trees_minPixels * depth / pixelsAtUnitDepth);
        // The crown's normal, turned towards the viewer (a card seen from behind).
        if (normal.z < 0.0)
            normal = -normal;
        for (int c = 0; c < 4; ++c)
        {
            vec2 corner = vec2(c == 1 || c == 3 ? 1.0 : -1.0, c >= 2 ? 1.0 : -1.0);
            vec3 p = view + vec3(corner * radius, 0.0);
            loa_scenePosition = scene;
            loa_viewPosition = p;
            loa_viewNormal = vec3(0.0, 0.0, 1.0);
            loa_texCoord = tc;
            loa_texCoord1 = normal.xy;
            loa_texCoord2 = corner;
            loa_color = color;
            gl_Position = gl_ProjectionMatrix * vec4(p, 1.0);
            EmitVertex();
        }
        EndPrimitive();
    }
}
