#version 450 compatibility
// Palette rendering outside the LoA pipeline (paper 003; osgLoA::PaletteMapping::createProgram):
// loa_plain.frag.glsl with the base texel replaced by the nearest colour (CIELab) of row
// level - 1 of the texture's palette (unit 5, osgLoA::PaletteMapping::attach). Same strategies
// as the "palette" graphic style (loa_style_palette.frag.glsl); the interest strategy reads
// loa_featureInterest (default 1: full detail). loa_palette_lit false writes the unlit colour
// (texture x vertex colour), for comparisons with the CPU (PaletteLookup).
// The lookup itself is loa_palette_baseColor of loa_style_palette.frag.glsl, linked into the same
// program (osgLoA::PaletteMapping::createProgram).
uniform bool loa_hasTexture = true; // as loa_plain.frag.glsl (also declared by the style file)
uniform vec3 loa_lightDirection = vec3(0.3, 0.5, 0.8); // towards the light, view space
uniform float loa_ambient = 0.35;
uniform bool loa_palette_lit = true;
uniform float loa_featureInterest = 1.0;

in vec3 loa_viewNormal;
in vec3 loa_viewPosition;
in vec2 loa_texCoord;
in vec4 loa_color;

layout(location = 0) out vec4 loa_fragColor;

vec4 loa_palette_baseColor(vec2 texCoord, vec4 color, vec3 viewPosition, vec3 viewNormal, float interest);

// The style's loa_styleColor (unused here) asks the usage scenario for the interest; outside a
// LoA node it is the uniform.
float loa_featureInterestOf(int j, vec3 p)
{
    return loa_featureInterest;
}

void main()
{
    vec3 n = normalize(loa_viewNormal);
    if (!gl_FrontFacing)
        n = -n;
    vec4 base = loa_palette_baseColor(loa_texCoord, loa_color, loa_viewPosition, n, loa_featureInterest);
    float light = 1.0;
    if (loa_palette_lit)
        light = loa_ambient + (1.0 - loa_ambient) * max(dot(n, normalize(loa_lightDirection)), 0.0);
    loa_fragColor = vec4(base.rgb * light, base.a);
}
