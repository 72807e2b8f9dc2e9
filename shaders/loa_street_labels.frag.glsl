#version 450 compatibility
// Street labels (osgLoA::StreetLabels): signed-distance-field glyphs (Green 2007) with a halo,
// box-filtered over the pixel, hidden where an opaque surface lies in front of the street.
uniform sampler2D loa_labelAtlas; // R8: 0.5 on outlines, +-0.5 at +-spread field texels
uniform sampler2D loa_labelDepth; // the G-buffer's front depth (window depth), viewport sized
uniform sampler2D loa_labelGlyphs; // RGBA32F, 1024 a row: each glyph's centre (pixels) and street depth
uniform bool loa_labelHasDepth = false;
uniform vec2 loa_labelDepthRange; // near, far
uniform bool loa_labelOrthographic = false;
uniform vec3 loa_labelColor;
uniform vec3 loa_labelHalo;
uniform float loa_labelHaloPixels;

in vec2 loa_atlasCoord;
flat in vec4 loa_glyphCentre;
flat in vec2 loa_field;
flat in ivec2 loa_labelSpan;

layout(location = 0) out vec4 loa_outColor;

float loa_labelLinearDepth(float d)
{
    float n = loa_labelDepthRange.x, f = loa_labelDepthRange.y;
    if (loa_labelOrthographic)
        return n + d * (f - n);
    return n * f / (f - d * (f - n));
}

// Whether an opaque surface lies in front of the street at pixel p (more than 2 % of the
// street's distance in front, or of the depth range in orthographic views: the street itself is
// in the G-buffer there).
bool loa_labelHidden(vec2 p, float streetDepth)
{
    float front = loa_labelLinearDepth(texelFetch(loa_labelDepth, ivec2(p), 0).r);
    float street = loa_labelLinearDepth(streetDepth);
    // Orthographic: 2 % of the depth range (the distance from the eye means nothing there).
    float tolerance = loa_labelOrthographic ? 0.02 * (loa_labelDepthRange.y - loa_labelDepthRange.x) : 0.02 * abs(street);
    return front < street - tolerance;
}

void main()
{
    // Every glyph centre of the label must be in view.
    if (loa_labelHasDepth)
        for (int i = loa_labelSpan.x; i < loa_labelSpan.x + loa_labelSpan.y; ++i)
        {
            vec4 g = texelFetch(loa_labelGlyphs, ivec2(i % 1024, i / 1024), 0);
            if (loa_labelHidden(g.xy, g.z))
                discard;
        }
    // Signed distance to the outline in window pixels (inside positive).
    float pixels = (texture(loa_labelAtlas, loa_atlasCoord).r - 0.5) / loa_field.x;
    float text = clamp(pixels + 0.5, 0.0, 1.0);
    float halo = clamp(pixels + min(loa_labelHaloPixels, loa_field.y) + 0.5, 0.0, 1.0);
    float opacity = loa_glyphCentre.w;
    if (halo * opacity <= 0.0)
        discard;
    loa_outColor = vec4((text * loa_labelColor + (halo - text) * loa_labelHalo) * opacity, halo * opacity);
}
