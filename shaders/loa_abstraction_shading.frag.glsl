#version 450 compatibility
// Object-space shading pass (paper 002 §3.1), quantized per fragment: the Gouraud shade s,
// interpolated from the vertices, is quantized to n levels, k = min(floor(s n), n - 1).
// Quantizing the interpolated value per fragment gives the level boundaries the paper obtains
// by subdividing polygons until each has one level (the iso-lines of the linear interpolation),
// without changing the geometry.
//  LOA_SHADING 1, cel: C = (k + 1) / n in RGB (osgLoA::AbstractionFormulas::celQuantize);
//      with LOA_ADAPTIVE, n = round(mix(far levels, focus levels, object importance)).
//  LOA_SHADING 2, pencil: S = layer k of the tonal pencil texture (layer 0 darkest), k from the
//      diffuse term max(n.l, 0) = (s - ambient) / (1 - ambient) instead of s, sampled in
//      model coordinates projected along the dominant axis of the model normal, times the
//      scale: coordinates fixed to the polygon (no shower-door effect).
#pragma import_defines(LOA_SHADING, LOA_ADAPTIVE)
#ifndef LOA_SHADING
#define LOA_SHADING 1
#endif
uniform int loa_abstraction_levels = 4;
uniform int loa_abstraction_levelsFar = 8;
uniform vec4 loa_objectImportance = vec4(0.0); // component loa_abstraction_slot is this node's
uniform int loa_abstraction_slot = 0;
uniform float loa_abstraction_pencilScale = 0.25;
uniform float loa_abstraction_ambient = 0.35;
uniform sampler2DArray loa_abstraction_pencil;

#pragma include "loa_abstraction_pass.glsl"

void main()
{
    if (!loa_materialCovers(loa_texCoord, loa_color))
        discard;
    float s = clamp(loa_gouraud, 0.0, 1.0);
#if defined(LOA_ADAPTIVE)
    float n = floor(mix(float(loa_abstraction_levelsFar), float(loa_abstraction_levels),
                        clamp(loa_objectImportance[loa_abstraction_slot], 0.0, 1.0)) + 0.5);
#else
    float n = float(loa_abstraction_levels);
#endif
#if LOA_SHADING == 1
    float k = min(floor(s * n), n - 1.0);
    float c = (k + 1.0) / n;
    loa_fragColor = vec4(c, c, c, 1.0);
#else
    // Pencil levels follow the diffuse term d = (s - ambient) / (1 - ambient) = max(n.l, 0), so
    // that surfaces turned from the light reach the darkest layer.
    float d = loa_abstraction_ambient < 1.0 ? (s - loa_abstraction_ambient) / (1.0 - loa_abstraction_ambient) : 1.0;
    float k = min(floor(clamp(d, 0.0, 1.0) * n), n - 1.0);
    vec3 a = abs(loa_objectNormal);
    vec2 uv = a.x >= a.y && a.x >= a.z ? loa_objectPosition.yz
            : (a.y >= a.z ? loa_objectPosition.xz : loa_objectPosition.xy);
    float tone = texture(loa_abstraction_pencil, vec3(uv * loa_abstraction_pencilScale, k)).r;
    loa_fragColor = vec4(tone, tone, tone, 1.0);
#endif
}
