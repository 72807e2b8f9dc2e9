#version 450 compatibility
// Blend weights of transition configurations (paper 004 §3.2.1), linked into every program that
// draws a feature in a configuration's style. Positions are in the LoA node's local ("scene")
// coordinates, Z up. The CPU twin is osgLoA::TransitionConfiguration / ScenarioEvaluator; the
// uniforms are filled by osgLoA::TransitionUniforms.
//
// Specialization (osgLoA::TransitionUniforms::applyScenario sets these defines on the LoA node):
//   LOA_INTEREST_GROUPS  number of distinct fragment-mode interests (0-4): each is evaluated once
//                        per fragment and shared by its configurations; absent: one evaluation
//                        per configuration (the generic path)
//   LOA_METRICS          bit k: some fragment-mode configuration has metric kind k (the others'
//                        code is compiled out)
#pragma import_defines(LOA_INTEREST_GROUPS, LOA_METRICS)
#ifndef LOA_METRICS
#define LOA_METRICS 31
#endif
//
// Scenario-wide uniforms (one value per LoA node):
uniform vec3 loa_eye;                  // the eye
uniform int loa_numConfigurations;     // <= 16
uniform vec4 loa_fade[16];             // fade-in begin, end; fade-out begin, end
uniform ivec4 loa_mode[16];            // x interpolation (0 fragment, 1 object, 2 group),
                                       // y combination (0 weighted mean, 1 min, 2 max),
                                       // z metrics present: bit k for kind k (see SaliencyMetric)
uniform vec4 loa_metricWeight[16];     // weights: view distance, view angle, region, focus
uniform float loa_interestWeight[16];  // weight of the feature-interest metric
uniform vec4 loa_rampA[16];            // near, far: view distance; near, far: view angle (deg)
uniform vec4 loa_rampB[16];            // near, far: region; near, far: focus
uniform sampler2D loa_regionMap;       // DistanceField: distance to the nearest region
uniform bool loa_hasRegionMap = false;
uniform vec4 loa_regionMapFrame;       // origin x, y; 1 / extent x, y (scene -> texture coords)
uniform float loa_regionMapScale = 1.0; // scene units per stored distance unit
uniform bool loa_hasFocus = false;
uniform vec3 loa_focusMin;
uniform vec3 loa_focusMax;
// Per-feature uniforms (set on the feature's state by the renderer):
uniform float loa_featureInterest;     // static interest after the scenario's overrides
uniform int loa_featureMatches;        // bit j: configuration j matches the feature
uniform float loa_featureWeights[16];  // raw weights of object/group matches, from the CPU
uniform float loa_featureInterests[16]; // their interests, from the CPU
uniform int loa_interestGroup[16];     // fragment-mode configuration's interest group, else -1
uniform int loa_groupConfiguration[4]; // a configuration of each interest group

const float LOA_INFINITY = 1.0e30;

// 1 at or below near, 0 at or above far, linear in between (a step when near == far).
float loa_ramp(float q, float nearValue, float farValue)
{
    if (q <= nearValue)
        return 1.0;
    if (q >= farValue)
        return 0.0;
    return 1.0 - (q - nearValue) / (farValue - nearValue);
}

// GLSL's smoothstep for a < b; the step x >= a for a zero-width interval (no division).
float loa_smoothstep(float a, float b, float x)
{
    if (!(b > a))
        return x >= a ? 1.0 : 0.0;
    return smoothstep(a, b, x);
}

float loa_blendFunction(vec4 fade, float interest)
{
    float fadeIn = loa_smoothstep(fade.x, fade.y, interest);
    float fadeOut = (fade.z >= 1.0 && interest <= 1.0) ? 1.0 : 1.0 - loa_smoothstep(fade.z, fade.w, interest);
    return fadeIn * fadeOut;
}

float loa_regionDistance(vec3 p)
{
    if (!loa_hasRegionMap)
        return LOA_INFINITY;
    vec2 uv = (p.xy - loa_regionMapFrame.xy) * loa_regionMapFrame.zw;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0))))
        return LOA_INFINITY;
    // Texels the flooding did not reach hold +infinity, and bilinear filtering next to them
    // (a + w (b - a)) gives NaN: both mean "farther than any ramp reaches".
    float d = texture(loa_regionMap, uv).r;
    return d < 1.0e29 ? d * loa_regionMapScale : LOA_INFINITY;
}

float loa_focusDistance(vec3 p)
{
    if (!loa_hasFocus)
        return LOA_INFINITY;
    vec3 d = max(max(loa_focusMin - p, p - loa_focusMax), vec3(0.0));
    return length(d);
}

// The combined interest of configuration j at scene position p. Metric kinds no fragment-mode
// configuration has are compiled out (LOA_METRICS); the rest are accumulated in scalars.
float loa_interest(int j, vec3 p)
{
    int present = loa_mode[j].z;
    float sum = 0.0, weights = 0.0, lo = 1.0, hi = 0.0;
    bool any = false;
#define LOA_ACCUMULATE(k, value, weight)                                                          \
    if ((present & (1 << k)) != 0)                                                              \
    {                                                                                            \
        float m_ = (value);                                                                      \
        sum += (weight) * m_;                                                                    \
        weights += (weight);                                                                     \
        lo = min(lo, m_);                                                                        \
        hi = max(hi, m_);                                                                        \
        any = true;                                                                              \
    }
    vec3 d = p - loa_eye;
#if (LOA_METRICS & 1) != 0
    LOA_ACCUMULATE(0, loa_ramp(length(d), loa_rampA[j].x, loa_rampA[j].y), loa_metricWeight[j].x)
#endif
#if (LOA_METRICS & 2) != 0
    LOA_ACCUMULATE(1, loa_ramp(degrees(atan(max(0.0, loa_eye.z - p.z), length(d.xy))), loa_rampA[j].z,
                               loa_rampA[j].w),
                   loa_metricWeight[j].y)
#endif
#if (LOA_METRICS & 4) != 0
    LOA_ACCUMULATE(2, loa_ramp(loa_regionDistance(p), loa_rampB[j].x, loa_rampB[j].y), loa_metricWeight[j].z)
#endif
#if (LOA_METRICS & 8) != 0
    LOA_ACCUMULATE(3, loa_ramp(loa_focusDistance(p), loa_rampB[j].z, loa_rampB[j].w), loa_metricWeight[j].w)
#endif
#if (LOA_METRICS & 16) != 0
    LOA_ACCUMULATE(4, clamp(loa_featureInterest, 0.0, 1.0), loa_interestWeight[j])
#endif
#undef LOA_ACCUMULATE
    if (!any)
        return 0.0;
    if (loa_mode[j].y == 1)
        return lo;
    if (loa_mode[j].y == 2)
        return hi;
    return weights > 0.0 ? sum / weights : 0.0;
}

// The interest configuration j uses for the current feature at p: per fragment in fragment
// mode, else the CPU's value for the feature (object) or its group.
float loa_featureInterestOf(int j, vec3 p)
{
    return loa_mode[j].x == 0 ? loa_interest(j, p) : loa_featureInterests[j];
}

// The raw (unnormalized) blend weight of configuration j for the current feature at p.
float loa_rawWeight(int j, vec3 p)
{
    if ((loa_featureMatches & (1 << j)) == 0)
        return 0.0;
    if (loa_mode[j].x != 0)
        return loa_featureWeights[j];
    return loa_blendFunction(loa_fade[j], loa_interest(j, p));
}

// The normalized blend weights of up to four configurations at once (js: their indices, -1 for
// none; the fused pass of TransitionRenderer asks for several, docs/rendering.md): one loop over
// the matches. Specialized (LOA_INTEREST_GROUPS): each interest group's interest once, every raw
// weight once; generic: one interest evaluation per configuration.
vec4 loa_blendWeights4(ivec4 js, vec3 p)
{
#ifdef LOA_INTEREST_GROUPS
    float g0 = 0.0, g1 = 0.0, g2 = 0.0, g3 = 0.0;
#if LOA_INTEREST_GROUPS > 0
    g0 = loa_interest(loa_groupConfiguration[0], p);
#endif
#if LOA_INTEREST_GROUPS > 1
    g1 = loa_interest(loa_groupConfiguration[1], p);
#endif
#if LOA_INTEREST_GROUPS > 2
    g2 = loa_interest(loa_groupConfiguration[2], p);
#endif
#if LOA_INTEREST_GROUPS > 3
    g3 = loa_interest(loa_groupConfiguration[3], p);
#endif
#endif
    float sum = 0.0;
    vec4 w = vec4(0.0);
    for (int k = 0; k < loa_numConfigurations; ++k)
    {
#ifdef LOA_INTEREST_GROUPS
        int g = loa_interestGroup[k];
        float interest = g == 0 ? g0 : (g == 1 ? g1 : (g == 2 ? g2 : g3));
        float r = g < 0 ? loa_featureWeights[k] : loa_blendFunction(loa_fade[k], interest);
        r = (loa_featureMatches & (1 << k)) != 0 ? r : 0.0;
#else
        float r = loa_rawWeight(k, p);
#endif
        sum += r;
        w = mix(w, vec4(r), equal(js, ivec4(k)));
    }
    return sum > 0.0 ? w / sum : vec4(0.0);
}

// The blend weight of configuration j, normalized over the feature's matching configurations
// (0 when none has weight here).
float loa_blendWeight(int j, vec3 p)
{
    return loa_blendWeights4(ivec4(j, -1, -1, -1), p).x;
}
