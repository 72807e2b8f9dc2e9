#version 450 compatibility
// Whether a fragment of the model covers its pixel, for the passes that write one surface per
// pixel (the abstraction node's object-ID, shading and unshaded passes): the model's alpha test
// (osg::AlphaFunc, mirrored by osgLoA::FixedFunctionUniforms as loa_alphaFunc / loa_alphaRef) on
// the material opacity (texture alpha x vertex alpha), and for blended materials (loa_blending:
// OSG's ac and obj readers blend textures with alpha instead of alpha-testing them) opacity of at
// least one half. Tree cards, billboards and fences then have their shape in the ID, edge and
// shading images, not the boxes of their quads.
uniform sampler2D loa_baseTexture;
uniform bool loa_hasTexture = false;
uniform int loa_alphaFunc = 0x0207; // GL_ALWAYS: no alpha test
uniform float loa_alphaRef = 0.0;
uniform bool loa_blending = false;

// The model's alpha test (osg::AlphaFunc, as the fixed function tests it) on an opacity; also
// linked into the LoA passes (loa_pass.frag.glsl, TransitionRenderer).
bool loa_alphaFuncPasses(float a)
{
    switch (loa_alphaFunc)
    {
    case 0x0200: return false;
    case 0x0201: return a < loa_alphaRef;
    case 0x0202: return a == loa_alphaRef;
    case 0x0203: return a <= loa_alphaRef;
    case 0x0204: return a > loa_alphaRef;
    case 0x0205: return a != loa_alphaRef;
    case 0x0206: return a >= loa_alphaRef;
    default: return true;
    }
}

bool loa_materialCovers(vec2 texCoord, vec4 color)
{
    float a = color.a;
    if (loa_hasTexture)
        a *= texture(loa_baseTexture, texCoord).a;
    return loa_alphaFuncPasses(a) && (!loa_blending || a >= 0.5);
}
