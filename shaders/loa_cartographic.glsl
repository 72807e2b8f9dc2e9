// The base of the cartographic styles (paper 004 §3.2.3; docs/styles.md): one colour of a
// qualitative ColorBrewer scheme (Brewer 1994) per feature type, or per sub-type under the
// scenario's colour scheme, and flat shading (the face normal
// from screen-space derivatives of the view position). CPU twin: GraphicStyle::cartographicColors,
// GraphicStyle::lightFactor.
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
uniform int loa_featureSubType; // osgLoA::FeatureSubType code, per feature (0: none)
// The scenario's colour scheme (osgLoA::ColorScheme): a colour per sub-type code, a = 1 + the
// feature type it is for (0: none). Unset (all 0): every feature in its type's colour.
uniform vec4 loa_cartographic_subTypeColors[64];

// The feature type of this draw, 0 (generic) when out of range.
int loa_cartographic_type()
{
    return (loa_featureType >= 0 && loa_featureType < 6) ? loa_featureType : 0;
}

// The feature's colour: its sub-type's under the scenario's scheme, else its type's. CPU twin:
// ColorScheme::colorOf.
vec3 loa_cartographic_color()
{
    int code = loa_featureSubType;
    int type = loa_cartographic_type();
    // a = 1 + the type the scheme's colour is for (0: none).
    if (code > 0 && code < 64 && int(round(loa_cartographic_subTypeColors[code].a)) == type + 1)
        return loa_cartographic_subTypeColors[code].rgb;
    return loa_cartographic_colors[type];
}

// The flat-shading factor ambient + (1 - ambient) max(n.l, 0) of the face at viewPosition.
float loa_cartographic_light(vec3 viewPosition, vec3 viewNormal)
{
    vec3 n = cross(dFdx(viewPosition), dFdy(viewPosition));
    float len = length(n);
    // Degenerate derivatives (a face seen edge-on): fall back to the interpolated normal.
    n = len > 1.0e-12 ? n / len : viewNormal;
    if (dot(n, viewNormal) < 0.0)
        n = -n; // face the viewer, as viewNormal does
    float ambient = loa_cartographic_ambient;
    return ambient + (1.0 - ambient) * max(dot(n, normalize(loa_lightDirection)), 0.0);
}
