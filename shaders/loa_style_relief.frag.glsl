#version 450 compatibility
// Graphic style "relief" (paper 004 §3.2.3, Figure 8D, after Buchin et al. 2004; osgLoA::
// ReliefPresentation, docs/styles.md): the cartographic style, with terrain drawn as a relief
// presentation computed from its geometry:
//  - slope lines (hachures): short strokes along the direction of steepest descent, one per cell
//    of a world-space grid whose cell is about loa_relief_cellPixels pixels on screen (the grid's
//    cell size is a power of two in world units; the two sizes around the target are blended, so
//    the density on screen stays the same at any distance); a cell holds a stroke with the
//    probability smoothstep(minSlope, maxSlope, slope), so steep slopes are dense and flat ground
//    empty; strokes are checked in the 3x3 cells around a fragment, so none is cut at a cell border;
//  - shadowed hachures: a stroke widens by up to loa_relief_shadowWidth pixels with the shade of
//    its slope under a light from the north-west (map convention), so shaded slopes read darker;
//  - loose lines: form lines at every loa_relief_contourInterval of height, faded out where they
//    would lie closer than loa_relief_contourPixels on screen.
// CPU twins: ReliefPresentation::downhill, slope, shade, density, cellSize, hachureCoverage.
#pragma include "loa_cartographic.glsl"

uniform mat4 loa_viewToScene; // view -> LoA node local coordinates (loa_style.vert.glsl)
uniform vec3 loa_relief_strokeColor = vec3(140.0, 81.0, 10.0) / 255.0; // BrBG dark brown
uniform float loa_relief_cellPixels = 14.0;
uniform float loa_relief_length = 0.8;  // stroke length, fraction of a cell
uniform float loa_relief_width = 1.0;   // pixels
uniform float loa_relief_shadowWidth = 1.5; // extra pixels at full shade
uniform float loa_relief_minSlope = 0.05; // tan of the slope angle
uniform float loa_relief_maxSlope = 0.5;
uniform vec3 loa_relief_lightDirection = vec3(-0.5, 0.5, 0.70710678); // towards the light, scene space
uniform float loa_relief_contourInterval = 5.0; // world units of height
uniform float loa_relief_contourPixels = 6.0;
uniform float loa_relief_contourStrength = 0.4;

float loa_relief_hash(vec2 c, float salt)
{
    return fract(sin(dot(c, vec2(127.1, 311.7)) + salt * 74.7) * 43758.5453);
}

// Coverage of the strokes of the cells of size `cell` around p (world x/y).
float loa_relief_strokes(vec2 p, vec2 down, float density, float widthWorld, float pixelWorld, float cell)
{
    vec2 perp = vec2(-down.y, down.x);
    vec2 base = floor(p / cell);
    float best = 0.0;
    for (int j = -1; j <= 1; ++j)
        for (int i = -1; i <= 1; ++i)
        {
            vec2 c = base + vec2(i, j);
            if (loa_relief_hash(c, 1.0) >= density)
                continue;
            // The stroke's centre: jittered within the middle half of its cell.
            vec2 centre = (c + 0.25 + 0.5 * vec2(loa_relief_hash(c, 2.0), loa_relief_hash(c, 3.0))) * cell;
            vec2 d = p - centre;
            float along = abs(dot(d, down)), across = abs(dot(d, perp));
            float halfLength = 0.5 * loa_relief_length * cell;
            float cover = clamp(0.5 * widthWorld / pixelWorld + 0.5 - across / pixelWorld, 0.0, 1.0) *
                          clamp(0.5 + (halfLength - along) / pixelWorld, 0.0, 1.0);
            best = max(best, cover);
        }
    return best;
}

vec4 loa_styleColor(vec3 scenePosition, vec3 viewPosition, vec3 viewNormal, vec2 texCoord, vec4 color)
{
    int type = loa_cartographic_type();
    vec3 base = loa_cartographic_color() * loa_cartographic_light(viewPosition, viewNormal);
    if (type != 5)
        return vec4(base, color.a);
    vec3 n = normalize(mat3(loa_viewToScene) * viewNormal);
    if (n.z < 0.0)
        n = -n; // terrain faces up
    float horizontal = length(n.xy);
    float slope = horizontal / max(n.z, 1.0e-3);
    // The upward normal leans downhill: its ground part is the direction of steepest descent.
    vec2 down = horizontal > 1.0e-6 ? n.xy / horizontal : vec2(0.0, -1.0);
    // World units per pixel on the ground.
    float pixelWorld = max(length(fwidth(scenePosition.xy)) * 0.70710678, 1.0e-6);
    float shade = 1.0 - max(dot(n, normalize(loa_relief_lightDirection)), 0.0);
    float density = smoothstep(loa_relief_minSlope, loa_relief_maxSlope, slope);
    float widthWorld = (loa_relief_width + loa_relief_shadowWidth * shade) * pixelWorld;
    float ink = 0.0;
    if (density > 0.0)
    {
        float level = log2(max(loa_relief_cellPixels * pixelWorld, 1.0e-6));
        float l0 = floor(level);
        float a = loa_relief_strokes(scenePosition.xy, down, density, widthWorld, pixelWorld, exp2(l0));
        float b = loa_relief_strokes(scenePosition.xy, down, density, widthWorld, pixelWorld, exp2(l0 + 1.0));
        ink = mix(a, b, level - l0);
    }
    if (loa_relief_contourInterval > 0.0 && slope > 1.0e-4)
    {
        float h = scenePosition.z / loa_relief_contourInterval;
        float distanceWorld = abs(h - round(h)) * loa_relief_contourInterval / slope; // on the ground
        float spacingPixels = loa_relief_contourInterval / (slope * pixelWorld);
        float line = clamp(0.5 * loa_relief_width + 0.5 - distanceWorld / pixelWorld, 0.0, 1.0);
        float fade = smoothstep(loa_relief_contourPixels, 2.0 * loa_relief_contourPixels, spacingPixels);
        ink = max(ink, loa_relief_contourStrength * line * fade);
    }
    return vec4(mix(base, loa_relief_strokeColor, ink), color.a);
}
