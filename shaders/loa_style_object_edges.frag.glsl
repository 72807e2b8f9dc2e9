#version 450 compatibility
// Graphic style "object-edges" (paper 004 §3.2.3, generic features: edge enhancement in image
// space and object space [DW03]; osgLoA::ObjectSpaceEdges): the cartographic style, with the
// creases, boundaries and silhouettes of the geometry (loa_object_edges.geom.glsl finds them)
// drawn over it as anti-aliased lines loa_objectEdges_width pixels wide: a crease is shared by the
// two faces beside it, each drawing half of it; a silhouette or boundary edge has one visible
// side, which draws it whole. The compositor's image-space edges stay on: the two combine.
#pragma include "loa_cartographic.glsl"

noperspective in vec3 loa_edgeDistance;
flat in int loa_edgeMask;
flat in int loa_edgeFull;
uniform float loa_objectEdges_width = 1.5;
uniform vec3 loa_objectEdges_color = vec3(0.1, 0.1, 0.1);

vec4 loa_styleColor(vec3 scenePosition, vec3 viewPosition, vec3 viewNormal, vec2 texCoord, vec4 color)
{
    vec3 base = loa_cartographic_color() * loa_cartographic_light(viewPosition, viewNormal);
    float coverage = 0.0;
    for (int k = 0; k < 3; ++k)
    {
        if ((loa_edgeMask & (1 << k)) == 0)
            continue;
        float halfWidth = ((loa_edgeFull & (1 << k)) != 0 ? 1.0 : 0.5) * loa_objectEdges_width;
        coverage = max(coverage, clamp(halfWidth + 0.5 - loa_edgeDistance[k], 0.0, 1.0));
    }
    return vec4(mix(base, loa_objectEdges_color, coverage), color.a);
}
