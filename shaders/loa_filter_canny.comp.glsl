#version 430
// The Canny edge detector (osgLoA::CannyFilter), LOA_CANNY_STAGE selects the pass:
//   0: Y = 0.299 R + 0.587 G + 0.114 B of input 0, blurred along x with the normalized one-sided
//      Gaussian weights loa_weights[0..LOA_RADIUS] (GaussianFilter::weightsFor);
//   1: input 0 (stage 0) blurred along y, then L = clamp(floor(255 s + 0.5), 0, 255);
//   2: the Sobel gradient of L (stage 1, 3x3, wrapped): (gx, gy, gx^2 + gy^2, 0), integers;
//   3: non-maximum suppression on input 0 (stage 2) with cv::Canny's direction quantization and
//      tie rule, then the double threshold on the squared magnitude (loa_lowSq, loa_highSq):
//      0 none, 0.5 weak, 1 strong in R, G, B;
//   4: one hysteresis step on input 0: a weak texel with a strong 8-neighbour becomes strong;
//   5: the edge image: 0 where input 0 is strong, 1 elsewhere; alpha from input 1 (the
//      filter's input).
// The arithmetic matches the CPU twin (CannyFilter::edgeClasses, hysteresis) operation for
// operation: `precise` keeps the driver from fusing multiply-adds, and from stage 2 on every
// value is a small integer (exact in float). No integer % anywhere; the direction choice is
// made with selects so that all lanes run the same code.
vec4 loa_fetch0(ivec2 p);
vec4 loa_fetch1(ivec2 p);
ivec2 loa_size();
ivec2 loa_wrapMode; // set by the pass contract's main (shaders/loa_filter_common.comp.glsl)

#if LOA_CANNY_STAGE == 0 || LOA_CANNY_STAGE == 1
uniform float loa_weights[LOA_RADIUS + 1];
#endif
#if LOA_CANNY_STAGE == 3
uniform int loa_lowSq;
uniform int loa_highSq;
#endif

#if LOA_CANNY_STAGE == 0
float loa_cannyValue(ivec2 p)
{
    vec3 c = loa_fetch0(p).rgb;
    precise float y = 0.299 * c.r + 0.587 * c.g + 0.114 * c.b;
    return y;
}
#else
float loa_cannyValue(ivec2 p) { return loa_fetch0(p).r; }
#endif

#if LOA_CANNY_STAGE <= 1
vec4 loa_filterTexel(ivec2 p)
{
    const ivec2 d = LOA_CANNY_STAGE == 0 ? ivec2(1, 0) : ivec2(0, 1);
    precise float s = loa_cannyValue(p) * loa_weights[0];
    for (int k = 1; k <= LOA_RADIUS; ++k)
    {
        precise float pair = loa_cannyValue(p + d * k) + loa_cannyValue(p - d * k);
        precise float term = pair * loa_weights[k];
        s = s + term;
    }
#if LOA_CANNY_STAGE == 1
    precise float scaled = s * 255.0 + 0.5;
    s = clamp(floor(scaled), 0.0, 255.0);
#endif
    return vec4(s, s, s, 1.0);
}
#elif LOA_CANNY_STAGE == 2
vec4 loa_filterTexel(ivec2 p)
{
    float a = loa_fetch0(p + ivec2(-1, -1)).r, b = loa_fetch0(p + ivec2(0, -1)).r;
    float c = loa_fetch0(p + ivec2(1, -1)).r, d = loa_fetch0(p + ivec2(-1, 0)).r;
    float f = loa_fetch0(p + ivec2(1, 0)).r, g = loa_fetch0(p + ivec2(-1, 1)).r;
    float h = loa_fetch0(p + ivec2(0, 1)).r, i = loa_fetch0(p + ivec2(1, 1)).r;
    float gx = (c + 2.0 * f + i) - (a + 2.0 * d + g);
    float gy = (g + 2.0 * h + i) - (a + 2.0 * b + c);
    return vec4(gx, gy, gx * gx + gy * gy, 0.0);
}
#elif LOA_CANNY_STAGE == 3
// m2 of a neighbour: 0 outside the region except along an axis that repeats (mode 0).
int loa_cannyNeighbour(ivec2 q)
{
    ivec2 n = loa_size();
    bool outX = (q.x < 0 || q.x >= n.x) && loa_wrapMode.x != 0;
    bool outY = (q.y < 0 || q.y >= n.y) && loa_wrapMode.y != 0;
    int m = int(loa_fetch0(q).b);
    return (outX || outY) ? 0 : m;
}

vec4 loa_filterTexel(ivec2 p)
{
    vec4 g = loa_fetch0(p);
    int gx = int(g.r), gy = int(g.g), m = int(g.b);
    int a = abs(gx), b = abs(gy);
    bool horizontal = 32768 * b < 13573 * a;
    bool vertical = !horizontal && 32768 * b > 79109 * a;
    bool diagonal = !horizontal && !vertical;
    int sx = (gx < 0) != (gy < 0) ? -1 : 1;
    ivec2 d = horizontal ? ivec2(1, 0) : (vertical ? ivec2(0, 1) : ivec2(sx, 1));
    int before = loa_cannyNeighbour(p - d), after = loa_cannyNeighbour(p + d);
    bool keep = m >= loa_lowSq && m > before && (diagonal ? m > after : m >= after);
    float c = keep ? (m >= loa_highSq ? 1.0 : 0.5) : 0.0;
    return vec4(c, c, c, 1.0);
}
#elif LOA_CANNY_STAGE == 4
vec4 loa_filterTexel(ivec2 p)
{
    float c = loa_fetch0(p).r;
    float s = max(max(max(loa_fetch0(p + ivec2(-1, -1)).r, loa_fetch0(p + ivec2(0, -1)).r),
                      max(loa_fetch0(p + ivec2(1, -1)).r, loa_fetch0(p + ivec2(-1, 0)).r)),
                  max(max(loa_fetch0(p + ivec2(1, 0)).r, loa_fetch0(p + ivec2(-1, 1)).r),
                      max(loa_fetch0(p + ivec2(0, 1)).r, loa_fetch0(p + ivec2(1, 1)).r)));
    float v = (c == 0.5 && s == 1.0) ? 1.0 : c;
    return vec4(v, v, v, 1.0);
}
#else
vec4 loa_filterTexel(ivec2 p)
{
    float v = loa_fetch0(p).r == 1.0 ? 0.0 : 1.0;
    return vec4(v, v, v, loa_fetch1(p).a);
}
#endif
