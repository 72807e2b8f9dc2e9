#version 450 compatibility
// Graphic style "cartographic" (paper 004 §3.2.3; osgLoA::GraphicStyle, docs/styles.md): one
// colour of a qualitative ColorBrewer scheme (Brewer 1994) per feature type, flat shading
// (loa_cartographic.glsl), no texture. Edges (Nienhaus & Döllner 2003) and depth unsharp masking
// (Luft et al. 2006) are added by the compositor from the style's edge / unsharp-mask parameters.
#pragma include "loa_cartographic.glsl"

vec4 loa_styleColor(vec3 scenePosition, vec3 viewPosition, vec3 viewNormal, vec2 texCoord, vec4 color)
{
    return vec4(loa_cartographic_color() *
                    loa_cartographic_light(viewPosition, viewNormal),
                color.a);
}
