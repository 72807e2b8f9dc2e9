#version 450 compatibility
// Composition of image-space / hybrid abstraction (osgLoA::AbstractionNode; papers 001, 002).
// Inputs, texel for pixel: the normal frame N (RGB, focus weight phi in alpha), the painterly
// image P (AbstractionLevelsFilter; N's colour without LOA_PAINTERLY), the edge image, the IDs,
// the object data (importance, scenario weight), the shading C or S, the base frame.
// Per pixel (osgLoA::AbstractionStyle::pixelParameters):
//   edge opacity a_e = mix(far, focus, phi) for screen focus, else the style's;
//   bleach a_b = bleaching (1 - phi); Sobel threshold t = mix(far, focus, phi) for object focus;
//   shading share s = mix(1, at focus, phi) for object focus, else 1.
// Edge image E (1 white, 0 line): DoG and Canny outputs as they are, Sobel: 0 where the
// magnitude >= t; LOA_SILHOUETTES: 0 where the left or lower neighbour has another object id (002 Fig. 4b;
// AbstractionFormulas::silhouettes: one-pixel lines).
// LOA_COMBINATION (osgLoA::AbstractionStyle, AbstractionFormulas), E' = 1 - a_e (1 - E),
// overlay(c) = mix(mix(c, 1, a_b), 0, 1 - E'):
//   0 overlay (001 §4.1): overlay(P);
//   1 shading only: cel overlay(N C), pencil overlay(S);
//   2 toon (002 Eq. 1): mix(clamp(P sigma mix(1, C, s) E'), 1, a_b);
//   3 pencil sketch (002 Eq. 2): overlay(clamp(P clamp(mix(1, S, s))^gamma)).
// LOA_WEIGHTED: mix(base, result, the object's scenario weight).
#pragma import_defines(LOA_COMBINATION, LOA_EDGES, LOA_SILHOUETTES, LOA_PAINTERLY, LOA_SHADING, LOA_WEIGHTED, LOA_ADAPTIVITY)
#ifndef LOA_COMBINATION
#define LOA_COMBINATION 0
#endif
#ifndef LOA_EDGES
#define LOA_EDGES 0
#endif
#ifndef LOA_SHADING
#define LOA_SHADING 0
#endif
#ifndef LOA_ADAPTIVITY
#define LOA_ADAPTIVITY 0
#endif
uniform sampler2D loa_abstraction_normal;
uniform sampler2D loa_abstraction_painterly;
uniform sampler2D loa_abstraction_edges;
uniform sampler2D loa_abstraction_ids;
uniform sampler2D loa_abstraction_objectData;
uniform sampler2D loa_abstraction_shading;
uniform sampler2D loa_abstraction_base;
uniform sampler2D loa_abstraction_surface; // view normal, view depth (0: no surface)
uniform float loa_abstraction_edgeOpacity = 1.0;
uniform float loa_abstraction_edgeOpacityFar = 0.2;
uniform float loa_abstraction_bleaching = 0.0;
uniform float loa_abstraction_sobelThreshold = 0.2;
uniform float loa_abstraction_sobelThresholdFar = 0.5;
uniform float loa_abstraction_brightening = 1.5;
uniform float loa_abstraction_pencilGamma = 2.0;
uniform float loa_abstraction_shadingAtFocus = 0.5;
uniform ivec2 loa_abstraction_origin = ivec2(0); // the viewport's origin: the textures start there
uniform bool loa_abstraction_stagesOk = true;      // false: the image stages failed, show N

layout(location = 0) out vec4 loa_fragColor;

vec3 loa_id(ivec2 p)
{
    ivec2 size = textureSize(loa_abstraction_ids, 0);
    return texelFetch(loa_abstraction_ids, clamp(p, ivec2(0), size - 1), 0).rgb;
}

// An object silhouette between p and q: another object id (or the background) where the
// surface is not continuous: normals more than ~18 degrees apart or depths more than 2 % apart.
// Objects that tile one surface (a game level's terrain pieces, a facade split into drawables)
// meet without a line.
bool loa_silhouette(ivec2 p, vec3 id, ivec2 q)
{
    if (all(equal(id, loa_id(q))))
        return false;
    ivec2 size = textureSize(loa_abstraction_surface, 0);
    vec4 a = texelFetch(loa_abstraction_surface, clamp(p, ivec2(0), size - 1), 0);
    vec4 b = texelFetch(loa_abstraction_surface, clamp(q, ivec2(0), size - 1), 0);
    if (a.w <= 0.0 || b.w <= 0.0) // the background on one side
        return true;
    return 1.0 - dot(a.xyz, b.xyz) > 0.05 || abs(a.w - b.w) > 0.02 * max(a.w, b.w);
}

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy) - loa_abstraction_origin;
    vec4 n = texelFetch(loa_abstraction_normal, p, 0);
    if (!loa_abstraction_stagesOk)
    {
        loa_fragColor = vec4(n.rgb, 1.0);
        return;
    }
    float phi = clamp(n.a, 0.0, 1.0);
#if LOA_ADAPTIVITY == 1
    float edgeOpacity = mix(loa_abstraction_edgeOpacityFar, loa_abstraction_edgeOpacity, phi);
#else
    float edgeOpacity = loa_abstraction_edgeOpacity;
#endif
    float bleach = loa_abstraction_bleaching * (1.0 - phi);
#if LOA_ADAPTIVITY == 2
    float threshold = mix(loa_abstraction_sobelThresholdFar, loa_abstraction_sobelThreshold, phi);
    float share = mix(1.0, loa_abstraction_shadingAtFocus, phi);
#else
    float threshold = loa_abstraction_sobelThreshold;
    float share = 1.0;
#endif
#if defined(LOA_PAINTERLY)
    vec3 P = texelFetch(loa_abstraction_painterly, p, 0).rgb;
#else
    vec3 P = n.rgb;
#endif
    float E = 1.0;
#if LOA_EDGES == 1 || LOA_EDGES == 3
    E = clamp(texelFetch(loa_abstraction_edges, p, 0).r, 0.0, 1.0);
#elif LOA_EDGES == 2
    E = texelFetch(loa_abstraction_edges, p, 0).r >= threshold ? 0.0 : 1.0;
#endif
#if defined(LOA_SILHOUETTES)
    vec3 c0 = loa_id(p);
    if (loa_silhouette(p, c0, p - ivec2(1, 0)) || loa_silhouette(p, c0, p - ivec2(0, 1)))
        E = 0.0;
#endif
#if LOA_SHADING != 0
    float shade = texelFetch(loa_abstraction_shading, p, 0).r;
#else
    float shade = 1.0;
#endif
    // E' = 1 - a_e (1 - E): the edge image at its opacity; overlay = mix(mix(c, 1, a_b), 0, 1 - E').
    float lines = edgeOpacity * (1.0 - E);
    vec3 c;
#if LOA_COMBINATION == 0
    c = mix(mix(P, vec3(1.0), bleach), vec3(0.0), lines);
#elif LOA_COMBINATION == 1
#if LOA_SHADING == 2
    // Pencil tones on white paper: where no surface was shaded (alpha 0, the background) the
    // normal frame shows through (the sky), so that lit faces, drawn white, stay visible
    // against it instead of vanishing into white paper.
    c = texelFetch(loa_abstraction_shading, p, 0).a > 0.5 ? vec3(shade) : n.rgb;
#else
    c = n.rgb * shade;
#endif
    c = mix(mix(c, vec3(1.0), bleach), vec3(0.0), lines);
#elif LOA_COMBINATION == 2
    c = clamp(P * loa_abstraction_brightening * mix(1.0, shade, share) * (1.0 - lines), 0.0, 1.0);
    c = mix(c, vec3(1.0), bleach);
#else
    c = clamp(P * pow(clamp(mix(1.0, shade, share), 0.0, 1.0), loa_abstraction_pencilGamma), 0.0, 1.0);
    c = mix(mix(c, vec3(1.0), bleach), vec3(0.0), lines);
#endif
#if defined(LOA_WEIGHTED)
    float w = texelFetch(loa_abstraction_objectData, p, 0).g;
    c = mix(texelFetch(loa_abstraction_base, p, 0).rgb, c, w);
#endif
    loa_fragColor = vec4(c, 1.0);
}
