#version 450 compatibility
// Graphic style "cartographic" (paper 004 §3.2.3; osgLoA::GraphicStyle, docs/styles.md): one
// colour of a qualitative ColorBrewer scheme (Brewer 1994) per feature type, flat shading
// (the face normal from screen-space derivatives of the view position), no texture. Edges
// (Nienhaus & Döllner 2003) and depth unsharp masking (Luft et al. 2006) are added by the
// compositor from the style's edge / unsharp-mask parameters.
uniform int loa_featureType; // osgLoA::FeatureType: 0 generic 1 building 2 street 3 water 4 green 5 terrain
uniform vec3 loa_lightDirection = vec3(0.3, 0.5, 0.8); // towards the light, view space
// Set3 grey, salmon, light yellow, blue, green; Pastel1 tan (GraphicStyle::cartographicColors).
uniform vec3 loa_cartographic_colors[6] = vec3[6](vec3(217.0, 217.0, 217.0) / 255.0,
                                                  vec3(251.0, 128.0, 114.0) / 255.0,
                                                  vec3(255.0, 255.0, 179.0) / 255.0,
                                                  vec3(128.0, 177.0, 211.0) / 255.0,
                                                  vec3(179.0, 222.0, 105.0) / 255.0,
                                                  vec3(229.0, 216.0, 189.0) / 255.0);
uniform float loa_cartographic_ambient = 0.6;

vec4 loa_styleColor(vec3 scenePosition, vec3 viewPosition, vec3 viewNormal, vec2 texCoord, vec4 color)
{
    vec3 n = cross(dFdx(viewPosition), dFdy(viewPosition));
    float len = length(n);
    // Degenerate derivatives (a face seen edge-on): fall back to the interpolated normal.
    n = len > 1.0e-12 ? n / len : viewNormal;
    if (dot(n, viewNormal) < 0.0)
        n = -n; // face the viewer, as viewNormal does
    int type = (loa_featureType >= 0 && loa_featureType < 6) ? loa_featureType : 0;
    float ambient = loa_cartographic_ambient;
    float diffuse = max(dot(n, normalize(loa_lightDirection)), 0.0);
    return vec4(loa_cartographic_colors[type] * (ambient + (1.0 - ambient) * diffuse), color.a);
}
