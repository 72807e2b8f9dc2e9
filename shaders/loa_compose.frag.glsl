#version 450 compatibility
// Image compositing of the LoA node (paper 004 §3.2.4, Algorithm 2; docs/rendering.md): per
// pixel the fragments of the stencil-routed A-buffer, the ping-pong buffer's fragment and the
// G-buffer's opaque colour are sorted by depth, fragments of one surface merged, and blended back
// to front; then edge enhancement from G-buffer discontinuities (Nienhaus & Doellner 2003) and
// unsharp masking of the depth buffer (Luft et al. 2006). The output is premultiplied and drawn
// over the framebuffer (ONE, ONE_MINUS_SRC_ALPHA): the background is what the camera drew before.
#pragma import_defines(LOA_MAX_FRAGMENTS, LOA_USE_ABUFFER)
#ifndef LOA_MAX_FRAGMENTS
#define LOA_MAX_FRAGMENTS 64
#endif
in vec2 loa_screenCoord;

uniform sampler2D loa_gColor;  // premultiplied colour of features drawn in the shared pass
uniform sampler2D loa_gNormal; // view normal * 0.5 + 0.5, unsharp strength
uniform sampler2D loa_gId;     // feature id, drawn flag
uniform sampler2D loa_gEdge;   // edge colour, strength
uniform sampler2D loa_gDepth;  // front depth
uniform sampler2D loa_unsharpBlur;  // blurred (alpha * linear depth, alpha), reduced resolution
uniform vec2 loa_unsharpScaleToTexture = vec2(1.0); // window coordinates -> its texture coordinates
uniform sampler2D loa_pingColor0;
uniform sampler2D loa_pingDepth0;
uniform sampler2D loa_pingColor1;
uniform sampler2D loa_pingDepth1;
uniform bool loa_usePingPong;
uniform bool loa_useEdges;
uniform bool loa_useUnsharp;
uniform vec2 loa_depthRange;   // near, far
uniform bool loa_orthographic = false;
uniform float loa_mergeEpsilon = 2.0e-6; // window depth: fragments this close are one surface
uniform vec4 loa_edgeThresholds = vec4(0.02, 0.08, 0.25, 0.6); // depth lo/hi (relative), normal lo/hi
uniform ivec2 loa_viewportOrigin = ivec2(0); // the pass targets' (0, 0) in window coordinates
uniform float loa_unsharpGain = 8.0;           // depth difference (scene extents) -> darkening ramp
uniform float loa_unsharpMaxDarkening = 0.4;   // the most unsharp masking darkens a colour

#ifdef LOA_USE_ABUFFER
int loa_abufferFetch(ivec2 pixel, inout vec4 colors[LOA_MAX_FRAGMENTS], inout float depths[LOA_MAX_FRAGMENTS],
                     int count);
vec4 loa_compositeLayers(int count, inout vec4 colors[LOA_MAX_FRAGMENTS], inout float depths[LOA_MAX_FRAGMENTS],
                         float mergeEpsilon);
#endif

layout(location = 0) out vec4 loa_outColor;

float loa_linearDepth(float d)
{
    float n = loa_depthRange.x, f = loa_depthRange.y;
    if (loa_orthographic)
        return n + d * (f - n);
    return n * f / (f - d * (f - n));
}

// A function of depth that is linear in screen space on planes: 1 / linear depth in perspective,
// linear depth in orthographic projections. Its Laplacian is zero on every plane.
float loa_planarDepth(ivec2 p)
{
    float d = loa_linearDepth(texelFetch(loa_gDepth, p, 0).r);
    return loa_orthographic ? d : 1.0 / d;
}

bool loa_drawn(ivec2 p)
{
    return texelFetch(loa_gId, p, 0).a > 0.5;
}

// Edge measure in [0, 1] of the front surface at p (0 where no surface is drawn).
float loa_edge(ivec2 p)
{
    ivec2 size = textureSize(loa_gDepth, 0);
    if (!loa_drawn(p))
        return 0.0;
    float d = loa_planarDepth(p);
    vec3 n = texelFetch(loa_gNormal, p, 0).xyz * 2.0 - 1.0;
    vec3 id = texelFetch(loa_gId, p, 0).rgb;
    const ivec2 offsets[4] = ivec2[4](ivec2(1, 0), ivec2(-1, 0), ivec2(0, 1), ivec2(0, -1));
    float laplace = 0.0, normalEdge = 0.0, idEdge = 0.0;
    for (int k = 0; k < 4; ++k)
    {
        ivec2 q = clamp(p + offsets[k], ivec2(0), size - 1);
        if (!loa_drawn(q))
        {
            idEdge = 1.0; // silhouette against the background
            laplace += d;
            continue;
        }
        float dq = loa_planarDepth(q);
        laplace += dq;
        vec3 nq = texelFetch(loa_gNormal, q, 0).xyz * 2.0 - 1.0;
        normalEdge = max(normalEdge, 1.0 - dot(n, nq));
        // A feature boundary is an edge where the surface is not continuous across it: two
        // features (or objects) tiling one surface, such as the many terrain pieces of a game
        // level, meet without a line (normals within ~18 degrees, depth within 2 %).
        if (any(greaterThan(abs(texelFetch(loa_gId, q, 0).rgb - id), vec3(0.5 / 255.0))) &&
            (1.0 - dot(n, nq) > 0.05 || abs(dq - d) > 0.02 * d))
            idEdge = 1.0;
    }
    // Second-order depth discontinuity, relative: zero on planes whatever their slope.
    float depthEdge = smoothstep(loa_edgeThresholds.x, loa_edgeThresholds.y, abs(4.0 * d - laplace) / d);
    normalEdge = smoothstep(loa_edgeThresholds.z, loa_edgeThresholds.w, normalEdge);
    return max(max(depthEdge, normalEdge), idEdge);
}

// The opaque colour of the shared pass at p as a straight-alpha fragment, if any.
bool loa_opaqueFragment(ivec2 p, out vec4 color, out float depth)
{
    vec4 c = texelFetch(loa_gColor, p, 0);
    color = c.a > 0.0 ? vec4(c.rgb / c.a, c.a) : vec4(0.0);
    depth = c.a > 0.0 ? texelFetch(loa_gDepth, p, 0).r : 1.0;
    return c.a > 0.0;
}

// Algorithm 2 line 11: the two ping-pong targets hold the same surface in successive styles.
bool loa_pingPongFragment(ivec2 p, out vec4 color, out float depth)
{
    vec4 c0 = texelFetch(loa_pingColor0, p, 0), c1 = texelFetch(loa_pingColor1, p, 0);
    float a = c0.a + c1.a;
    float d0 = c0.a > 0.0 ? texelFetch(loa_pingDepth0, p, 0).r : 1.0;
    float d1 = c1.a > 0.0 ? texelFetch(loa_pingDepth1, p, 0).r : 1.0;
    color = a > 0.0 ? vec4((c0.rgb * c0.a + c1.rgb * c1.a) / a, min(a, 1.0)) : vec4(0.0);
    depth = min(d0, d1);
    return a > 0.0;
}

// Without the A-buffer, at most two fragments: the operations of loa_compositeLayers (stable
// sort by depth, merge of one surface, back-to-front blend) on scalars, without the local arrays
// (which llvmpipe keeps in memory and reads and writes lane by lane).
vec4 loa_composeWithoutABuffer(ivec2 p)
{
    vec4 front, back = vec4(0.0);
    float frontDepth, backDepth = 1.0;
    bool any = loa_opaqueFragment(p, front, frontDepth);
    vec4 c;
    float d;
    if (loa_usePingPong && loa_pingPongFragment(p, c, d))
    {
        if (!any)
        {
            front = c;
            frontDepth = d;
        }
        else
        {
            bool nearer = d < frontDepth;
            back = nearer ? front : c;
            backDepth = nearer ? frontDepth : d;
            front = nearer ? c : front;
            frontDepth = nearer ? d : frontDepth;
            if (loa_mergeEpsilon >= 0.0 && backDepth - frontDepth <= loa_mergeEpsilon)
            {
                float sumA = front.a + back.a;
                front = vec4((front.rgb * front.a + back.rgb * back.a) / sumA, min(1.0, sumA));
                back = vec4(0.0);
            }
        }
        any = true;
    }
    if (!any)
        discard;
    return vec4(mix(back.rgb * back.a, front.rgb, front.a), mix(back.a, 1.0, front.a));
}

#ifdef LOA_USE_ABUFFER
// All fragments of the pixel (G-buffer, ping-pong, A-buffer), sorted, merged and blended.
vec4 loa_composeWithABuffer(ivec2 p)
{
    vec4 colors[LOA_MAX_FRAGMENTS];
    float depths[LOA_MAX_FRAGMENTS];
    int count = 0;
    if (loa_opaqueFragment(p, colors[count], depths[count]))
        ++count;
    if (loa_usePingPong && loa_pingPongFragment(p, colors[count], depths[count]))
        ++count;
    count = loa_abufferFetch(p, colors, depths, count);
    if (count == 0 && loa_drawn(p))
    {
        // An opaque front surface without a single routed fragment: on renderers that route by
        // raster coverage (llvmpipe; StencilRoutedABuffer::RASTER_COVERAGE) a pixel that an edge
        // cuts can lose its fragments. Its neighbours' fragments stand in (at most 4 fetches, only
        // at such pixels) instead of the background showing through.
        const ivec2 offsets[4] = ivec2[4](ivec2(1, 0), ivec2(-1, 0), ivec2(0, 1), ivec2(0, -1));
        ivec2 size = textureSize(loa_gDepth, 0);
        for (int k = 0; k < 4 && count == 0; ++k)
            count = loa_abufferFetch(clamp(p + offsets[k], ivec2(0), size - 1), colors, depths, 0);
    }
    if (count == 0)
        discard;
    return loa_compositeLayers(count, colors, depths, loa_mergeEpsilon);
}
#endif

void main()
{
    vec2 local = gl_FragCoord.xy - vec2(loa_viewportOrigin);
    ivec2 p = ivec2(local);
#ifdef LOA_USE_ABUFFER
    vec4 result = loa_composeWithABuffer(p);
#else
    vec4 result = loa_composeWithoutABuffer(p);
#endif
    if (loa_mergeEpsilon >= 0.0 && loa_drawn(p) && result.a > 0.0 && result.a < 0.999)
    {
        // The front surface is opaque here (the G-buffer's coverage: its visible styles' weights
        // sum to 1), so the fragments must sum to full opacity; where routing lost some of them
        // (edge pixels under raster coverage) the ones that arrived stand for the surface. The
        // paper's literal Algorithm 2 (loa_mergeEpsilon < 0) is left as it is: it lets the
        // background through at surfaces of several styles (docs/rendering.md).
        result /= result.a;
    }
    if (loa_useEdges && loa_drawn(p))
    {
        // Only pixels whose style asks for edges look at their neighbours.
        vec4 edge = texelFetch(loa_gEdge, p, 0);
        float e = edge.a > 0.0 ? loa_edge(p) * edge.a : 0.0;
        if (e > 0.0)
            result.rgb = mix(result.rgb, edge.rgb / max(edge.a, 1.0e-3) * result.a, clamp(e, 0.0, 1.0));
    }
    if (loa_useUnsharp && loa_drawn(p))
    {
        // Unsharp masking of the depth buffer (Luft et al. 2006; paper 004 §3.2.4): the spatial
        // importance dD = G * D - D, with D the linear depth in units of the scene's depth extent
        // (far - near of the fitted range: the LoA node's bounding sphere), so that dD is bounded
        // by 1 and the same building gap darkens the same from near and far. Only the negative
        // part (the neighbourhood is in front) darkens. The blur is alpha-weighted (a G-buffer
        // coverage-weighted mean) and the darkening is weighted by the pixel's blend alpha, as the
        // paper does to reduce ringing; at most loa_unsharpMaxDarkening of the colour is taken, so
        // no surface goes black beside a near occluder.
        float strength = texelFetch(loa_gNormal, p, 0).a;
        vec2 blur = texture(loa_unsharpBlur, local / loa_unsharpScaleToTexture).rg;
        if (strength > 0.0 && blur.y > 0.0)
        {
            float d = loa_linearDepth(texelFetch(loa_gDepth, p, 0).r);
            float extent = max(loa_depthRange.y - loa_depthRange.x, 1.0e-6);
            float spatialImportance = (blur.x / blur.y - d) / extent; // < 0: the neighbourhood is in front
            float t = clamp(-loa_unsharpGain * spatialImportance, 0.0, 1.0);
            float darkening = loa_unsharpMaxDarkening * clamp(strength, 0.0, 1.0) * clamp(result.a, 0.0, 1.0) * t;
            result.rgb *= 1.0 - darkening;
        }
    }
    loa_outColor = result;
}
