#version 450 compatibility
// The fragment stage's main of every feature draw (docs/rendering.md). The renderer inserts one
// of these defines after the #version line:
//   LOA_PASS_GBUFFER_COLOR  front-surface G-buffer, the feature drawn in its one style (shared pass)
//   LOA_PASS_GBUFFER_DEPTH  front-surface G-buffer, depth/normal/id where the feature is opaque
//   LOA_PASS_ABUFFER        one configuration's draw into the stencil-routed A-buffer
//   LOA_PASS_PINGPONG       one configuration's opaque draw into a ping-pong target
//   LOA_PASS_GBUFFER_FUSED  front-surface G-buffer, a feature in transition drawn once with the
//                           blend of its configurations' styles (loa_fusedColor, generated per
//                           combination of styles by TransitionRenderer)
// and LOA_UNFEATURED with LOA_PASS_GBUFFER_COLOR for geometry outside every feature (weight 1),
// LOA_COVERED with it for features whose configuration's weight is > 0 all over their box.
in vec3 loa_scenePosition;
in vec3 loa_viewPosition;
in vec3 loa_viewNormal;
in vec2 loa_texCoord;
in vec4 loa_color;

uniform int loa_configuration;       // the configuration this draw belongs to
uniform int loa_numConfigurations;
uniform int loa_visibleStyles;       // bit j: configuration j's style draws (is not hidden)
uniform vec4 loa_styleEdge[16];      // edge colour (rgb) and strength (a) of configuration j's style
uniform float loa_styleUnsharp[16];  // unsharp-masking strength of configuration j's style
uniform uint loa_featureId;
uniform sampler2D loa_baseTexture;
uniform bool loa_hasTexture = false; // unit 0 has a texture (osgLoA::FixedFunctionUniforms)
uniform int loa_texEnvMode = 0;      // unit 0's texture environment: 0 modulate, 1 replace, 2 decal, 3 add, 4 blend
uniform bool loa_styleUsesTexture = true; // the configuration's style reads the model's texture
uniform int loa_alphaFunc = 0x0207;  // the model's alpha test (GL comparison; GL_ALWAYS: none)
uniform float loa_alphaRef = 0.0;
uniform bool loa_blending = false;   // the model blends (GL_BLEND) where this is drawn
uniform sampler2D loa_frontDepth;    // the G-buffer's depth (A-buffer and ping-pong passes)
uniform float loa_depthEpsilon = 2.0e-6; // window-depth tolerance of "at the front surface"

// The scenario's regions drawn as lines over every style's colour (osgLoA::RouteLine).
#pragma include "loa_route_line.glsl"

float loa_blendWeight(int j, vec3 p);

#if defined(LOA_PASS_GBUFFER_COLOR) || defined(LOA_PASS_ABUFFER) || defined(LOA_PASS_PINGPONG)
vec4 loa_styleColor(vec3 scenePosition, vec3 viewPosition, vec3 viewNormal, vec2 texCoord, vec4 color);
#endif
#ifdef LOA_PASS_ABUFFER
void loa_abufferWrite(vec4 straightAlphaColor);
#endif

#ifdef LOA_PASS_GBUFFER_FUSED
// The weighted sum of the configurations' style colours (rgb), edges and unsharp strengths;
// alpha: the sum of the weights.
vec4 loa_fusedColor(vec3 scenePosition, vec3 viewPosition, vec3 viewNormal, vec2 texCoord, vec4 color,
                    out vec4 edge, out float unsharp);
#endif

#if defined(LOA_PASS_GBUFFER_COLOR) || defined(LOA_PASS_GBUFFER_DEPTH) || defined(LOA_PASS_GBUFFER_FUSED)
layout(location = 0) out vec4 loa_outColor;  // premultiplied colour of shared draws
layout(location = 1) out vec4 loa_outNormal; // view normal * 0.5 + 0.5, unsharp strength
layout(location = 2) out vec4 loa_outId;     // feature id (24 bits), drawn flag
layout(location = 3) out vec4 loa_outEdge;   // edge colour x strength, strength
#endif
#ifdef LOA_PASS_PINGPONG
layout(location = 0) out vec4 loa_outColor; // straight colour, alpha = blend weight
#endif

vec3 loa_facingNormal()
{
    vec3 n = normalize(loa_viewNormal);
    return gl_FrontFacing ? n : -n;
}

// The opacity of the model's own material: vertex alpha and the texture's alpha as unit 0's
// texture environment combines them (the fixed function: decal keeps the fragment's alpha,
// replace takes the texture's, the other modes multiply).
float loa_materialOpacity()
{
    float a = loa_color.a;
    if (loa_hasTexture)
    {
        float t = texture(loa_baseTexture, loa_texCoord).a;
        a = loa_texEnvMode == 2 ? a : (loa_texEnvMode == 1 ? t : a * t);
    }
    return a;
}

// The model's alpha test on its material opacity (osg::AlphaFunc, as the fixed function tests
// it): alpha-tested cards, fences and billboards keep their shape in every pass and style.
bool loa_alphaFuncPasses(float a); // loa_material_alpha.frag.glsl
bool loa_alphaTestPasses()
{
    return loa_alphaFunc == 0x0207 || loa_alphaFuncPasses(loa_materialOpacity());
}

// Drops fragments hidden behind the G-buffer's front surface. The tolerance grows with the
// surface's depth slope (two pixels' worth): the multisampled A-buffer and the single-sampled
// G-buffer do not rasterize the same fragments at every pixel (coverage at sample positions vs.
// the pixel centre), so where the front triangle has no A-buffer fragment the one that is there
// belongs to its neighbour, a little behind. Measured on the view-angle scenario at 640x480: a
// fixed tolerance of 2e-6 dropped them on 7,676 pixels of far terrain, which showed the
// background as speckles; this tolerance leaves 55 (docs/rendering.md).
void loa_discardBehindFront()
{
    float front = texelFetch(loa_frontDepth, ivec2(gl_FragCoord.xy), 0).r;
    if (gl_FragCoord.z > front + loa_depthEpsilon + 2.0 * fwidth(gl_FragCoord.z))
        discard;
}

#if defined(LOA_PASS_GBUFFER_COLOR) || defined(LOA_PASS_GBUFFER_DEPTH) || defined(LOA_PASS_GBUFFER_FUSED)
// The edge colour weighted by its strength, and the strength: sums of these over styles give the
// strength-weighted mean colour (rgb / a) and the blended strength (a).
vec4 loa_premultipliedEdge(int j)
{
    return vec4(loa_styleEdge[j].rgb * loa_styleEdge[j].a, loa_styleEdge[j].a);
}

void loa_writeGeometry(vec4 edge, float unsharp)
{
    loa_outNormal = vec4(loa_facingNormal() * 0.5 + 0.5, clamp(unsharp, 0.0, 1.0));
    uint id = loa_featureId & 0xffffffu;
    loa_outId = vec4(float(id & 0xffu), float((id >> 8) & 0xffu), float((id >> 16) & 0xffu), 255.0) / 255.0;
    loa_outEdge = edge;
}
#endif

void main()
{
    loa_routeLineDerivatives(loa_scenePosition); // before any discard
    if (!loa_alphaTestPasses())
        discard;
#if defined(LOA_PASS_GBUFFER_COLOR)
#if !defined(LOA_UNFEATURED) && !defined(LOA_COVERED)
    // The feature's one contributing configuration: its weight is 1 wherever it is non-zero.
    // LOA_COVERED: the CPU proved the weight > 0 all over the feature's box (no test needed).
    if (loa_blendWeight(loa_configuration, loa_scenePosition) <= 0.0)
        discard;
#endif
    vec4 c = loa_styleColor(loa_scenePosition, loa_viewPosition, loa_facingNormal(), loa_texCoord, loa_color);
    loa_outColor = vec4(loa_routeLine(c.rgb, loa_scenePosition, loa_facingNormal()), 1.0);
    loa_writeGeometry(loa_premultipliedEdge(loa_configuration), loa_styleUnsharp[loa_configuration]);
#elif defined(LOA_PASS_GBUFFER_FUSED)
    // Only features whose contributing configurations are all visible and opaque come here, on
    // opaque materials: their weights sum to 1 (normalized over the feature's matches), so the
    // blend is the surface's colour, as the A-buffer's merged fragments of one surface give it.
    vec4 edge;
    float unsharp;
    vec4 c = loa_fusedColor(loa_scenePosition, loa_viewPosition, loa_facingNormal(), loa_texCoord, loa_color, edge,
                            unsharp);
    if (c.a <= 0.0)
        discard;
    loa_outColor = vec4(loa_routeLine(c.rgb / c.a, loa_scenePosition, loa_facingNormal()), 1.0);
    loa_writeGeometry(edge / c.a, unsharp / c.a);
#elif defined(LOA_PASS_GBUFFER_DEPTH)
    // Front surface only where the feature is opaque: its visible styles' weights sum to 1.
    float visible = 0.0, unsharp = 0.0;
    vec4 edge = vec4(0.0);
    for (int j = 0; j < loa_numConfigurations; ++j)
    {
        if ((loa_visibleStyles & (1 << j)) == 0)
            continue;
        float w = loa_blendWeight(j, loa_scenePosition);
        visible += w;
        edge += w * loa_premultipliedEdge(j);
        unsharp += w * loa_styleUnsharp[j];
    }
    // (Only features of opaque materials come here: without blending the fixed function ignores
    // alpha, and the alpha test above has dropped what it drops.)
    if (visible < 0.999)
        discard;
    loa_outColor = vec4(0.0);
    loa_writeGeometry(edge, unsharp);
#else
    float w = loa_blendWeight(loa_configuration, loa_scenePosition);
    if (w <= 0.0)
        discard;
    loa_discardBehindFront();
    vec4 c = loa_styleColor(loa_scenePosition, loa_viewPosition, loa_facingNormal(), loa_texCoord, loa_color);
    c.rgb = loa_routeLine(c.rgb, loa_scenePosition, loa_facingNormal());
    // Alpha makes a surface translucent only where the model blends (GL_BLEND), as in the fixed
    // function; elsewhere the style's colour is opaque and only the alpha test drops fragments.
    // Where it blends, a style that ignores the texture (cartographic, blueprint) takes its alpha
    // bounded by the material's opacity, so that alpha-blended cut-outs (tree cards, a skyline
    // backdrop) keep their shape instead of showing their whole quads (found by loa-bench's frame
    // check on TORCS street-1: 2.6 % more of the frame covered than plain). Styles that read the
    // texture have its alpha in theirs, through the model's texture environment.
    float a = loa_blending ? (loa_styleUsesTexture ? c.a : min(c.a, loa_materialOpacity())) : 1.0;
#ifdef LOA_PASS_ABUFFER
    loa_abufferWrite(vec4(c.rgb, a * w));
#else
    if (a < 0.5)
        discard; // opaque draws: alpha-tested
    loa_outColor = vec4(c.rgb, w);
#endif
#endif
}
