#version 450 compatibility
// Focus pass (osgLoA::AbstractionNode): writes the focus weight phi of each pixel into the
// normal frame's alpha (blending keeps the frame's RGB: BlendFunc(ZERO, ONE, ONE, ZERO)), where
// the image filters read it.
//  LOA_ADAPTIVITY 0 (uniform): phi = 0, the strongest level everywhere;
//  1 (screen focus, paper 001): phi = 1 - smoothstep(inner, outer, |p - f| / diagonal), and with
//    LOA_SEGMENTATION phi = 1 on the focus object's pixels (001 §4.2);
//  2 (object focus, paper 002 §4): phi = the importance of the pixel's object (ID pass).
#pragma import_defines(LOA_ADAPTIVITY, LOA_SEGMENTATION)
#ifndef LOA_ADAPTIVITY
#define LOA_ADAPTIVITY 0
#endif
uniform sampler2D loa_abstraction_ids;
uniform sampler2D loa_abstraction_objectData;
uniform vec2 loa_abstraction_focusPixel;
uniform vec2 loa_abstraction_size;
uniform float loa_abstraction_innerRadius = 0.1;
uniform float loa_abstraction_outerRadius = 0.5;
uniform vec3 loa_abstraction_focusId = vec3(-1.0); // the focus object's id colour x 255

layout(location = 0) out vec4 loa_fragColor;

float loa_focusWeight(float d)
{
    if (loa_abstraction_outerRadius <= loa_abstraction_innerRadius)
        return d < loa_abstraction_innerRadius ? 1.0 : 0.0;
    return 1.0 - smoothstep(loa_abstraction_innerRadius, loa_abstraction_outerRadius, d);
}

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    float phi = 0.0;
#if LOA_ADAPTIVITY == 1
    float d = length(gl_FragCoord.xy - loa_abstraction_focusPixel) / length(loa_abstraction_size);
    phi = loa_focusWeight(d);
#if defined(LOA_SEGMENTATION)
    vec3 id = floor(texelFetch(loa_abstraction_ids, p, 0).rgb * 255.0 + 0.5);
    if (all(equal(id, loa_abstraction_focusId)))
        phi = 1.0;
#endif
#elif LOA_ADAPTIVITY == 2
    phi = texelFetch(loa_abstraction_objectData, p, 0).r;
#endif
    loa_fragColor = vec4(0.0, 0.0, 0.0, phi);
}
