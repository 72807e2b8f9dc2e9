// The scenario's regions drawn as lines on the ground (paper 004 Figure 9C and §4.1: the route on
// the map), included by loa_pass.frag.glsl and applied to every style's colour. The CPU twin and
// the texture layout are osgLoA::RouteLine (osgLoA/transitions/RouteLine); docs/cartographic.md.
//
// loa_routeLines (unit RouteLine::kUnit, RGBA32F, RouteLine::kTextureWidth texels a row, three
// groups of loa_routeLineRows rows): segment k is texel k of each group: its end points (a.x, a.y,
// b.x, b.y; scene frame), its colour (r, g, b, opacity) and its width in pixels (x).
uniform sampler2D loa_routeLines;
uniform int loa_routeLineCount = 0;  // segments; 0: nothing drawn (no texel fetched)
uniform int loa_routeLineRows = 0;   // rows of each group
uniform mat4 loa_viewToScene;        // view -> scene (loa_style.vert.glsl)
uniform mat4 loa_sceneToView;        // its inverse
uniform int loa_featureType;         // osgLoA::FeatureType: drawn on 2-5 (street, water, green, terrain)

// Window pixels per unit of normalized device coordinates (half the viewport's size), from the
// screen derivatives of the fragment's own NDC, taken by loa_routeLineDerivatives() at the start
// of main (before any discard, in uniform control flow).
vec2 loa_routePixelsPerNdc = vec2(0.0);

vec4 loa_routeSceneToClip(vec3 p)
{
    return gl_ProjectionMatrix * (loa_sceneToView * vec4(p, 1.0));
}

void loa_routeLineDerivatives(vec3 scenePosition)
{
    vec4 c = loa_routeSceneToClip(scenePosition);
    vec2 ndc = c.xy / c.w;
    loa_routePixelsPerNdc = vec2(1.0 / dFdx(ndc.x), 1.0 / dFdy(ndc.y));
}

vec4 loa_routeTexel(int index, int rowOffset)
{
    const int w = 4096; // RouteLine::kTextureWidth
    return texelFetch(loa_routeLines, ivec2(index % w, rowOffset + index / w), 0);
}

// The segment's end point a clipped towards b where its clip w is below wMin (a positive
// fraction of the fragment's own w, so that the lerp keeps precision in float).
vec4 loa_routeClipNear(vec4 a, vec4 b, float wMin)
{
    if (a.w >= wMin)
        return a;
    return mix(a, b, (wMin - a.w) / (b.w - a.w));
}

// The line's colour over rgb at scene position p (normal in view space). Each segment is taken to
// the horizontal plane through the fragment and projected to the window (clipped at the near
// side); the distance in pixels from the fragment to the projected segment is exact for level
// ground at any distance and slant, and a close estimate on slopes. Coverage is a one-pixel ramp
// (anti-aliased). A line at least 4 px wide has a casing, its colour at 55 %, 1 px on each side.
vec3 loa_routeLine(vec3 rgb, vec3 p, vec3 viewNormal)
{
    // Ground features only (street, water, green, terrain): not buildings, nor generic or
    // unfeatured geometry, whose up-facing faces may be roofs.
    if (loa_routeLineCount <= 0 || loa_featureType < 2 || loa_featureType > 5)
        return rgb;
    vec3 sceneNormal = mat3(loa_viewToScene) * viewNormal;
    if (sceneNormal.z < 0.5 * length(sceneNormal))
        return rgb; // walls and overhangs: the line lies on the ground
    if (any(isinf(loa_routePixelsPerNdc)) || any(isnan(loa_routePixelsPerNdc)))
        return rgb; // no screen derivatives (lines, points)
    vec4 cp = loa_routeSceneToClip(p);
    vec2 here = cp.xy / cp.w * loa_routePixelsPerNdc;
    // Parts of a segment nearer than a twentieth of the fragment's depth are left out.
    float wMin = 0.05 * cp.w;
    // The segment whose line covers the fragment most: the largest half width minus distance.
    float bestMargin = -1.0e30, bestPixels = 1.0e30;
    int bestIndex = -1;
    for (int k = 0; k < loa_routeLineCount; ++k)
    {
        vec4 s = loa_routeTexel(k, 0);
        vec4 ca = loa_routeSceneToClip(vec3(s.xy, p.z)), cb = loa_routeSceneToClip(vec3(s.zw, p.z));
        if (ca.w < wMin && cb.w < wMin)
            continue; // behind the eye or too near it
        vec4 na = loa_routeClipNear(ca, cb, wMin), nb = loa_routeClipNear(cb, ca, wMin);
        vec2 a = na.xy / na.w * loa_routePixelsPerNdc - here, b = nb.xy / nb.w * loa_routePixelsPerNdc - here;
        vec2 ab = b - a;
        float len2 = dot(ab, ab);
        float t = len2 > 0.0 ? clamp(-dot(a, ab) / len2, 0.0, 1.0) : 0.0;
        float pixels = length(a + ab * t);
        float margin = 0.5 * loa_routeTexel(k, 2 * loa_routeLineRows).x - pixels;
        if (margin > bestMargin)
        {
            bestMargin = margin;
            bestPixels = pixels;
            bestIndex = k;
        }
    }
    if (bestIndex < 0)
        return rgb;
    vec4 color = loa_routeTexel(bestIndex, loa_routeLineRows);
    float width = loa_routeTexel(bestIndex, 2 * loa_routeLineRows).x;
    float halfWidth = 0.5 * width;
    float cover = clamp(halfWidth + 0.5 - bestPixels, 0.0, 1.0) * color.a;
    if (cover <= 0.0)
        return rgb;
    vec3 fill = color.rgb;
    vec3 line = width >= 4.0 ? mix(0.55 * fill, fill, clamp(halfWidth - 0.5 - bestPixels, 0.0, 1.0)) : fill;
    return mix(rgb, line, cover);
}
