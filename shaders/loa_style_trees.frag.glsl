#version 450 compatibility
// Graphic style "trees" (paper 004 §3.2.3, Figure 8C, after Deussen & Strothotte 2000;
// osgLoA::TreeSilhouettes): the cartographic style, with tree crowns drawn as round leaf sprites
// (loa_tree_sprites.geom.glsl makes them) in the feature's cartographic colour, shaded by the
// crown's normal at the sprite (a sphere of foliage lit from loa_lightDirection); the outlines come
// from the compositor's depth-discontinuity edges. Everything else is drawn as "cartographic".
#pragma include "loa_cartographic.glsl"

uniform bool loa_treeCrown = false;
in vec2 loa_texCoord1; // the crown's view normal (x, y) at the sprite
in vec2 loa_texCoord2; // the fragment's place in its sprite, [-1, 1]^2

vec4 loa_styleColor(vec3 scenePosition, vec3 viewPosition, vec3 viewNormal, vec2 texCoord, vec4 color)
{
    if (!loa_treeCrown)
        return vec4(loa_cartographic_color() * loa_cartographic_light(viewPosition, viewNormal), color.a);
    if (dot(loa_texCoord2, loa_texCoord2) > 1.0)
        discard;
    vec3 n = vec3(loa_texCoord1, sqrt(max(0.0, 1.0 - dot(loa_texCoord1, loa_texCoord1))));
    float ambient = loa_cartographic_ambient;
    float light = ambient + (1.0 - ambient) * max(dot(n, normalize(loa_lightDirection)), 0.0);
    return vec4(loa_cartographic_color() * light, color.a);
}
