#version 430
// One line pass of the domain transform recursive filter (osgLoA::DomainTransformFilter,
// Gastal and Oliveira 2011 §5.2): LOA_LINES 1 filters a row, 2 a column, of input 0 in place in
// the output: forward J[n] = mix(F[n], J[n-1], w_n), then backward K[n] = mix(J[n], K[n+1],
// w_n+1), with w_n = exp(loa_lnA d_n) and d_n = 1 + loa_ratio sum_c |I_c(n) - I_c(n-1)| from the
// filter's input I (input 1). Clamp starts at the edge texel; repeat and mirror start from the
// periodic steady state of the wrapped line (period n, or 2n for mirror). The CPU twin is
// filterLine in DomainTransformFilter.cpp.
vec4 loa_fetch0(ivec2 p);
vec4 loa_fetch1(ivec2 p);
vec4 loa_load(ivec2 p);
void loa_store(ivec2 p, vec4 v);
ivec2 loa_size();
ivec2 loa_wrapped(ivec2 p);

uniform float loa_lnA;  // ln a = -sqrt(2) / sigma_H_i
uniform float loa_ratio; // sigma_s / sigma_r

ivec2 loa_at(int line, int i) { return LOA_LINES == 1 ? ivec2(i, line) : ivec2(line, i); }

/** w between positions i-1 and i of the line. */
float loa_weight(int line, int i)
{
    vec3 d = abs(loa_fetch1(loa_at(line, i)).rgb - loa_fetch1(loa_at(line, i - 1)).rgb);
    return exp(loa_lnA * (1.0 + loa_ratio * (d.r + d.g + d.b)));
}

/** The wrap mode along the line (0 repeat, 1 clamp, 2 mirror), read off where positions -1 and
 *  -2 wrap to (lines of one texel are the same under every mode). */
int loa_lineMode(int line)
{
    int origin = LOA_LINES == 1 ? loa_wrapped(loa_at(line, 0)).x : loa_wrapped(loa_at(line, 0)).y;
    int m1 = (LOA_LINES == 1 ? loa_wrapped(loa_at(line, -1)).x : loa_wrapped(loa_at(line, -1)).y) - origin;
    int m2 = (LOA_LINES == 1 ? loa_wrapped(loa_at(line, -2)).x : loa_wrapped(loa_at(line, -2)).y) - origin;
    if (m1 != 0) return 0;
    return m2 != 0 ? 2 : 1;
}

void loa_filterLine(int line)
{
    int n = LOA_LINES == 1 ? loa_size().x : loa_size().y;
    int mode = loa_lineMode(line);
    bool periodic = mode != 1 && n > 1;
    int period = mode == 2 ? 2 * n : n;

    vec3 prev;
    if (periodic)
    {
        // The state after one period from 0 is alpha + beta J[-1]; the steady state solves it.
        vec3 acc = vec3(0.0);
        float beta = 1.0;
        for (int i = -period; i < 0; ++i)
        {
            float w = loa_weight(line, i);
            acc = mix(loa_fetch0(loa_at(line, i)).rgb, acc, w);
            beta *= w;
        }
        prev = acc / (1.0 - beta);
    }
    else
        prev = loa_fetch0(loa_at(line, 0)).rgb;
    for (int i = 0; i < n; ++i)
    {
        vec4 c = loa_fetch0(loa_at(line, i));
        prev = mix(c.rgb, prev, loa_weight(line, i));
        loa_store(loa_at(line, i), vec4(prev, c.a));
    }

    vec3 next;
    if (periodic)
    {
        vec3 acc = vec3(0.0);
        float beta = 1.0;
        for (int i = n + period - 1; i >= n; --i)
        {
            float w = loa_weight(line, i + 1);
            acc = mix(loa_load(loa_at(line, i)).rgb, acc, w);
            beta *= w;
        }
        next = acc / (1.0 - beta);
    }
    else
        next = loa_load(loa_at(line, n - 1)).rgb;
    for (int i = n - 1; i >= 0; --i)
    {
        vec4 j = loa_load(loa_at(line, i));
        next = mix(j.rgb, next, loa_weight(line, i + 1));
        loa_store(loa_at(line, i), vec4(next, j.a));
    }
}
