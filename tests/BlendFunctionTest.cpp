// BlendFunction (paper 004 §3.2.1, Figure 6): smoothstep fades, hard steps, touching and
// overlapping intervals, validation, and mayContribute against brute-force sampling. Every
// expected number is computed by hand in the comment beside it.
#include <osgLoA/transitions/BlendFunction>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

using namespace osgLoA;

namespace
{
const float kNaN = std::numeric_limits<float>::quiet_NaN();

// smoothstep(a, b, x) = t²(3 - 2t), t = (x - a)/(b - a), written out independently in double.
double referenceSmoothstep(double a, double b, double x)
{
    double t = (x - a) / (b - a);
    t = std::min(1.0, std::max(0.0, t));
    return t * t * (3.0 - 2.0 * t);
}
} // namespace

TEST(BlendFunctionTest, SmoothstepAtHandComputedPoints)
{
    // t = 0.25: 0.25² (3 - 0.5) = 0.0625 * 2.5 = 0.15625
    EXPECT_FLOAT_EQ(BlendFunction::smoothstep(0.0f, 1.0f, 0.25f), 0.15625f);
    // t = 0.5: 0.25 * 2 = 0.5
    EXPECT_FLOAT_EQ(BlendFunction::smoothstep(0.0f, 1.0f, 0.5f), 0.5f);
    // t = 0.75: 0.5625 * 1.5 = 0.84375
    EXPECT_FLOAT_EQ(BlendFunction::smoothstep(0.0f, 1.0f, 0.75f), 0.84375f);
    // Interval [0.2, 0.6], x = 0.3: t = 0.1/0.4 = 0.25 -> 0.15625
    EXPECT_NEAR(BlendFunction::smoothstep(0.2f, 0.6f, 0.3f), 0.15625f, 1e-6f);
    // x = 0.5: t = 0.3/0.4 = 0.75 -> 0.84375
    EXPECT_NEAR(BlendFunction::smoothstep(0.2f, 0.6f, 0.5f), 0.84375f, 1e-6f);
    // Clamped outside the interval: 0 below, 1 above, exactly at the ends.
    EXPECT_EQ(BlendFunction::smoothstep(0.2f, 0.6f, 0.2f), 0.0f);
    EXPECT_EQ(BlendFunction::smoothstep(0.2f, 0.6f, -5.0f), 0.0f);
    EXPECT_EQ(BlendFunction::smoothstep(0.2f, 0.6f, 0.6f), 1.0f);
    EXPECT_EQ(BlendFunction::smoothstep(0.2f, 0.6f, 7.0f), 1.0f);
    // b <= a: the step x >= a.
    EXPECT_EQ(BlendFunction::smoothstep(0.4f, 0.4f, 0.4f), 1.0f);
    EXPECT_EQ(BlendFunction::smoothstep(0.4f, 0.4f, std::nextafter(0.4f, 0.0f)), 0.0f);
    EXPECT_EQ(BlendFunction::smoothstep(0.4f, 0.3f, 0.35f), 0.0f);
    EXPECT_EQ(BlendFunction::smoothstep(0.4f, 0.3f, 0.45f), 1.0f);
    EXPECT_EQ(BlendFunction::smoothstep(0.0f, 1.0f, kNaN), 0.0f);
}

TEST(BlendFunctionTest, FadeInFadeOutAndWeight)
{
    const BlendFunction f(0.2f, 0.4f, 0.6f, 0.8f);
    EXPECT_TRUE(f.validate().empty()) << f.validate();
    EXPECT_FALSE(f.isHard());
    // I = 0.25: fade-in t = 0.05/0.2 = 0.25 -> 0.15625; fade-out 1 (below 0.6).
    EXPECT_NEAR(f.fadeIn(0.25f), 0.15625f, 1e-6f);
    EXPECT_EQ(f.fadeOut(0.25f), 1.0f);
    EXPECT_NEAR(f.weight(0.25f), 0.15625f, 1e-6f);
    // I = 0.3: t = 0.5 -> 0.5.
    EXPECT_NEAR(f.weight(0.3f), 0.5f, 1e-6f);
    // I = 0.5: fully inside both: 1 * 1.
    EXPECT_EQ(f.weight(0.5f), 1.0f);
    // I = 0.65: fade-out t = 0.05/0.2 = 0.25 -> 1 - 0.15625 = 0.84375.
    EXPECT_NEAR(f.fadeOut(0.65f), 0.84375f, 1e-6f);
    EXPECT_NEAR(f.weight(0.65f), 0.84375f, 1e-6f);
    // I = 0.75: t = 0.75 -> 1 - 0.84375 = 0.15625.
    EXPECT_NEAR(f.weight(0.75f), 0.15625f, 1e-6f);
    // Outside the validity range: 0 (at 0.2 the fade-in is 0, at 0.8 the fade-out is 0).
    EXPECT_EQ(f.weight(0.1f), 0.0f);
    EXPECT_EQ(f.weight(0.2f), 0.0f);
    EXPECT_EQ(f.weight(0.8f), 0.0f);
    EXPECT_EQ(f.weight(1.0f), 0.0f);
    // weight = fadeIn * (1 - smoothstep(fade-out)) at many points, against the reference.
    for (int i = 0; i <= 1000; ++i)
    {
        const float x = float(i) / 1000.0f;
        const double expected = referenceSmoothstep(0.2, 0.4, x) * (1.0 - referenceSmoothstep(0.6, 0.8, x));
        EXPECT_NEAR(f.weight(x), expected, 2e-6) << "I = " << x;
        EXPECT_EQ(f.weight(x), f.fadeIn(x) * f.fadeOut(x)) << "I = " << x;
    }
}

// A zero-width interval is a step: no NaN, no division by zero; closed at the lower hard
// edge, open at the upper one.
TEST(BlendFunctionTest, HardTransitionsAreSteps)
{
    const BlendFunction f(0.3f, 0.3f, 0.7f, 0.7f);
    EXPECT_TRUE(f.isHard());
    EXPECT_TRUE(f.validate().empty()) << f.validate();
    EXPECT_EQ(f.weight(std::nextafter(0.3f, 0.0f)), 0.0f);
    EXPECT_EQ(f.weight(0.3f), 1.0f); // closed at the lower edge
    EXPECT_EQ(f.weight(0.5f), 1.0f);
    EXPECT_EQ(f.weight(std::nextafter(0.7f, 0.0f)), 1.0f);
    EXPECT_EQ(f.weight(0.7f), 0.0f); // open at the upper edge
    EXPECT_EQ(f.weight(0.9f), 0.0f);
    for (int i = 0; i <= 1000; ++i)
    {
        const float w = f.weight(float(i) / 1000.0f);
        EXPECT_TRUE(w == 0.0f || w == 1.0f) << w;
    }
}

// The top of the axis: a fade-out beginning at 1 never ends the range, so interest 1 is valid.
TEST(BlendFunctionTest, TopOfTheAxisStaysValid)
{
    const BlendFunction top(0.7f, 0.7f, 1.0f, 1.0f);
    EXPECT_EQ(top.weight(1.0f), 1.0f);
    EXPECT_EQ(top.weight(0.7f), 1.0f);
    EXPECT_EQ(top.weight(std::nextafter(0.7f, 0.0f)), 0.0f);
    // The default function is valid everywhere on [0, 1], both ends included.
    const BlendFunction all;
    EXPECT_TRUE(all.validate().empty());
    EXPECT_EQ(all.weight(0.0f), 1.0f);
    EXPECT_EQ(all.weight(1.0f), 1.0f);
    // A smooth fade-in up to the top: 1 at interest 1.
    const BlendFunction smoothTop(0.6f, 0.75f, 1.0f, 1.0f);
    EXPECT_EQ(smoothTop.weight(1.0f), 1.0f);
    // A fade-out beyond the top (outEnd > 1) is valid and leaves interest 1 at full weight.
    const BlendFunction beyond(0.0f, 0.0f, 1.0f, 1.5f);
    EXPECT_TRUE(beyond.validate().empty()) << beyond.validate();
    EXPECT_EQ(beyond.weight(1.0f), 1.0f);
}

// Two successive hard configurations touching at e: exactly one of them draws every interest.
TEST(BlendFunctionTest, TouchingHardEdgesNeverDrawTwice)
{
    const BlendFunction low(0.0f, 0.0f, 0.5f, 0.5f), high(0.5f, 0.5f, 1.0f, 1.0f);
    EXPECT_EQ(low.weight(0.5f), 0.0f); // the one fading in owns the edge
    EXPECT_EQ(high.weight(0.5f), 1.0f);
    for (int i = 0; i <= 1000; ++i)
    {
        const float x = float(i) / 1000.0f;
        EXPECT_EQ(low.weight(x) + high.weight(x), 1.0f) << "I = " << x;
    }
}

// Smooth transition: A's fade-out equals B's fade-in, so w_A + w_B = (1 - s) + s = 1 across
// the interval. In float, 1 - s is exact for s >= 0.5 (Sterbenz) and off by at most 2^-25
// below, which rounds back to 1 in the sum: the sum is exactly 1.
TEST(BlendFunctionTest, TouchingSmoothIntervalsSumToExactlyOne)
{
    const BlendFunction a(0.0f, 0.0f, 0.3f, 0.7f), b(0.3f, 0.7f, 1.0f, 1.0f);
    for (int i = 0; i <= 10000; ++i)
    {
        const float x = float(i) / 10000.0f;
        EXPECT_EQ(a.weight(x) + b.weight(x), 1.0f) << "I = " << x;
    }
    // The three levels of the built-in "distance" scenario: cartographic [0, 0.25..0.4],
    // abstract [0.25..0.4, 0.6..0.75], photorealistic [0.6..0.75, 1].
    const BlendFunction low(0.0f, 0.0f, 0.25f, 0.4f), mid(0.25f, 0.4f, 0.6f, 0.75f),
        high(0.6f, 0.75f, 1.0f, 1.0f);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int i = 0; i < 20000; ++i)
    {
        const float x = i == 0 ? 0.0f : (i == 1 ? 1.0f : u(rng));
        EXPECT_EQ(low.weight(x) + mid.weight(x) + high.weight(x), 1.0f) << "I = " << x;
    }
    // At the middle of the first transition, 0.325: t = 0.5, each gets 0.5.
    EXPECT_NEAR(low.weight(0.325f), 0.5f, 1e-6f);
    EXPECT_NEAR(mid.weight(0.325f), 0.5f, 1e-6f);
}

TEST(BlendFunctionTest, ValidationNamesTheViolatedCondition)
{
    EXPECT_EQ(BlendFunction(0.2f, 0.6f, 0.4f, 0.8f).validate(),
              "fade-in interval [0.2, 0.6] overlaps fade-out interval [0.4, 0.8]");
    EXPECT_EQ(BlendFunction(0.6f, 0.4f, 0.8f, 0.9f).validate(), "fade-in interval [0.6, 0.4] is inverted");
    EXPECT_EQ(BlendFunction(0.1f, 0.2f, 0.9f, 0.7f).validate(), "fade-out interval [0.9, 0.7] is inverted");
    EXPECT_EQ(BlendFunction(0.5f, 0.5f, 0.5f, 0.5f).validate(),
              "validity range is empty: fade-in and fade-out are the same step at 0.5");
    EXPECT_EQ(BlendFunction(-0.1f, 0.2f, 0.5f, 0.6f).validate(),
              "fade-in begins at -0.1, outside the interest axis [0, 1]");
    EXPECT_EQ(BlendFunction(1.5f, 1.5f, 2.0f, 2.0f).validate(),
              "fade-in begins at 1.5, outside the interest axis [0, 1]");
    EXPECT_EQ(BlendFunction(0.0f, kNaN, 1.0f, 1.0f).validate(), "a fade interval bound is not finite");
    EXPECT_EQ(BlendFunction(0.0f, 0.0f, 1.0f, std::numeric_limits<float>::infinity()).validate(),
              "a fade interval bound is not finite");
    // Touching intervals (inEnd == outBegin) are valid, and so is the single point at the top.
    EXPECT_EQ(BlendFunction(0.2f, 0.5f, 0.5f, 0.8f).validate(), "");
    EXPECT_EQ(BlendFunction(1.0f, 1.0f, 1.0f, 1.0f).validate(), "");
    EXPECT_EQ(BlendFunction(1.0f, 1.0f, 1.0f, 1.0f).weight(1.0f), 1.0f);
}

// An empty validity range draws nothing anywhere.
TEST(BlendFunctionTest, EmptyValidityRangeHasNoWeight)
{
    const BlendFunction f(0.5f, 0.5f, 0.5f, 0.5f);
    for (int i = 0; i <= 1000; ++i)
        EXPECT_EQ(f.weight(float(i) / 1000.0f), 0.0f);
}

// mayContribute is exact for functions that do not validate too (bind() rejects them, but the
// answer must not claim a draw that weight() never gives): an empty validity range ([0.5, 0.5]
// twice: I >= 0.5 and I < 0.5 never both hold) and inverted ones, where weight() is 0.
TEST(BlendFunctionTest, MayContributeIsExactForInvalidFunctions)
{
    for (const BlendFunction& f :
         {BlendFunction(0.5f, 0.5f, 0.5f, 0.5f), BlendFunction(0.8f, 0.8f, 0.5f, 0.5f),
          BlendFunction(0.8f, 0.9f, 0.2f, 0.4f)})
    {
        bool any = false;
        for (int i = 0; i <= 1000; ++i)
            any = any || f.weight(float(i) / 1000.0f) > 0.0f;
        EXPECT_FALSE(any);
        EXPECT_FALSE(f.mayContribute(0.0f, 1.0f))
            << "[" << f.inBegin << ", " << f.inEnd << "] [" << f.outBegin << ", " << f.outEnd << "]";
    }
}

// Invalid functions still evaluate to finite values in [0, 1] (an inverted interval acts as a
// step at its begin).
TEST(BlendFunctionTest, InvalidFunctionsEvaluateFinite)
{
    const BlendFunction inverted(0.6f, 0.4f, 0.3f, 0.1f);
    EXPECT_FALSE(inverted.validate().empty());
    // fade-in is the step I >= 0.6, fade-out 1 - (I >= 0.3).
    EXPECT_EQ(inverted.fadeIn(0.59f), 0.0f);
    EXPECT_EQ(inverted.fadeIn(0.6f), 1.0f);
    EXPECT_EQ(inverted.fadeOut(0.29f), 1.0f);
    EXPECT_EQ(inverted.fadeOut(0.3f), 0.0f);
    const BlendFunction weird[] = {inverted, BlendFunction(0.2f, 0.6f, 0.4f, 0.8f),
                                   BlendFunction(0.9f, 0.1f, 0.5f, 0.5f),
                                   BlendFunction(-1.0f, -2.0f, 3.0f, -4.0f)};
    for (const BlendFunction& f : weird)
        for (int i = -100; i <= 1100; ++i)
        {
            const float w = f.weight(float(i) / 1000.0f);
            EXPECT_TRUE(std::isfinite(w) && w >= 0.0f && w <= 1.0f) << w;
        }
}

TEST(BlendFunctionTest, NaNInterestGivesZero)
{
    for (const BlendFunction& f :
         {BlendFunction(), BlendFunction(0.2f, 0.4f, 0.6f, 0.8f), BlendFunction(0.3f, 0.3f, 0.7f, 0.7f)})
    {
        EXPECT_EQ(f.fadeIn(kNaN), 0.0f);
        EXPECT_EQ(f.fadeOut(kNaN), 0.0f);
        EXPECT_EQ(f.weight(kNaN), 0.0f);
        EXPECT_FALSE(f.mayContribute(kNaN, 1.0f));
        EXPECT_FALSE(f.mayContribute(0.0f, kNaN));
    }
    // An empty interval [hi < lo] contributes nothing.
    EXPECT_FALSE(BlendFunction().mayContribute(0.6f, 0.4f));
}

namespace
{
/** A random valid blend function: sorted bounds in [0, 1], with zero widths (hard edges), a
 *  fade-out at the top ([1, 1]) and a fade-out beyond the top drawn often. */
BlendFunction randomValidFunction(std::mt19937& rng)
{
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::uniform_int_distribution<int> coin(0, 3);
    float v[4] = {u(rng), u(rng), u(rng), u(rng)};
    std::sort(v, v + 4);
    if (coin(rng) == 0) v[1] = v[0];         // hard fade-in
    if (coin(rng) == 0) v[3] = v[2];         // hard fade-out
    if (coin(rng) == 0) v[2] = v[3] = 1.0f;  // valid up to the top
    if (coin(rng) == 0) v[0] = v[1] = 0.0f;  // valid from the bottom
    if (coin(rng) == 0) v[3] = v[2] + 0.25f; // fade-out past the top of the axis
    if (coin(rng) == 0) v[1] = v[2] = v[1];  // touching fade-in and fade-out
    BlendFunction f(v[0], v[1], v[2], v[3]);
    if (!f.validate().empty()) f = BlendFunction(v[0], v[1], std::max(v[1], 1.0f), std::max(v[1], 1.0f));
    return f;
}

/** Whether some interest in [lo, hi] gets a weight > 0, by sampling: n evenly spaced points with
 *  both ends, plus each bound of the function and its float neighbours where they lie in [lo, hi]
 *  (w > 0 on an interval whose ends are function bounds, so these catch tiny overlaps). */
bool sampledContribution(const BlendFunction& f, float lo, float hi, int n)
{
    std::vector<float> xs;
    for (int i = 0; i <= n; ++i)
        xs.push_back(lo + (hi - lo) * float(i) / float(n));
    xs.push_back(hi);
    for (float b : {f.inBegin, f.inEnd, f.outBegin, f.outEnd, 1.0f})
        for (float x : {std::nextafter(b, -1.0f), b, std::nextafter(b, 2.0f)})
            xs.push_back(x);
    for (float x : xs)
        if (x >= lo && x <= hi && f.weight(x) > 0.0f) return true;
    return false;
}
} // namespace

// mayContribute(lo, hi) is exact: true iff some interest of [lo, hi] gets a weight > 0.
TEST(BlendFunctionTest, MayContributeMatchesBruteForceSampling)
{
    std::mt19937 rng(2012);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    int positives = 0, negatives = 0;
    for (int trial = 0; trial < 4000; ++trial)
    {
        const BlendFunction f = randomValidFunction(rng);
        ASSERT_TRUE(f.validate().empty()) << f.validate();
        for (int k = 0; k < 10; ++k)
        {
            float lo = u(rng), hi = u(rng);
            if (lo > hi) std::swap(lo, hi);
            if (k == 0) hi = lo; // a single point
            const bool sampled = sampledContribution(f, lo, hi, 200);
            EXPECT_EQ(f.mayContribute(lo, hi), sampled)
                << "f = [" << f.inBegin << ", " << f.inEnd << "] [" << f.outBegin << ", " << f.outEnd
                << "], [" << lo << ", " << hi << "]";
            (sampled ? positives : negatives)++;
        }
    }
    // Both answers were exercised many times.
    EXPECT_GT(positives, 5000);
    EXPECT_GT(negatives, 5000);
}

// Subintervals that end exactly on, or one float beside, each bound of the function: the
// places where an off-by-one comparison (> against >=) would show.
TEST(BlendFunctionTest, MayContributeIsExactAtTheBounds)
{
    const BlendFunction functions[] = {
        BlendFunction(0.2f, 0.4f, 0.6f, 0.8f),  BlendFunction(0.3f, 0.3f, 0.7f, 0.7f),
        BlendFunction(0.3f, 0.3f, 0.7f, 0.9f),  BlendFunction(0.2f, 0.5f, 0.5f, 0.5f),
        BlendFunction(0.5f, 0.5f, 1.0f, 1.0f),  BlendFunction(0.0f, 0.0f, 1.0f, 1.0f),
        BlendFunction(0.6f, 0.75f, 1.0f, 1.0f), BlendFunction(0.0f, 0.0f, 0.25f, 0.4f)};
    for (const BlendFunction& f : functions)
    {
        std::vector<float> points = {0.0f, 1.0f};
        for (float b : {f.inBegin, f.inEnd, f.outBegin, f.outEnd})
            for (float x : {std::nextafter(b, -1.0f), b, std::nextafter(b, 2.0f)})
                if (x >= 0.0f && x <= 1.0f) points.push_back(x);
        for (float lo : points)
            for (float hi : points)
            {
                if (hi < lo) continue;
                const bool sampled = sampledContribution(f, lo, hi, 100);
                // Never a false negative: a weighted interest in [lo, hi] must be reported.
                if (sampled)
                {
                    EXPECT_TRUE(f.mayContribute(lo, hi))
                        << "[" << f.inBegin << ", " << f.inEnd << "] [" << f.outBegin << ", " << f.outEnd
                        << "] on [" << lo << ", " << hi << "]";
                }
                // False positives only where float rounding ends a smooth fade-out early: within
                // 1e-4 of the fade-out's width before outEnd, 1 - smoothstep rounds to 0 (3(1-t)² <
                // 2^-25), while the exact weight is still > 0.
                else if (f.mayContribute(lo, hi))
                {
                    EXPECT_GT(lo, f.outEnd - 1e-4f * (f.outEnd - f.outBegin))
                        << "[" << f.inBegin << ", " << f.inEnd << "] [" << f.outBegin << ", " << f.outEnd
                        << "] on [" << lo << ", " << hi << "]";
                }
            }
    }
    // Hand cases. Smooth fade-in [0.2, 0.4]: 0 at 0.2, > 0 just above.
    const BlendFunction s(0.2f, 0.4f, 0.6f, 0.8f);
    EXPECT_FALSE(s.mayContribute(0.0f, 0.2f));
    EXPECT_TRUE(s.mayContribute(0.0f, std::nextafter(0.2f, 1.0f)));
    EXPECT_FALSE(s.mayContribute(0.8f, 1.0f));
    // Hard fade-in at 0.3: interest 0.3 itself contributes (closed lower edge).
    const BlendFunction h(0.3f, 0.3f, 0.7f, 0.7f);
    EXPECT_TRUE(h.mayContribute(0.0f, 0.3f));
    EXPECT_FALSE(h.mayContribute(0.0f, std::nextafter(0.3f, 0.0f)));
    // Hard fade-out at 0.7: 0.7 itself does not (open upper edge).
    EXPECT_FALSE(h.mayContribute(0.7f, 1.0f));
    EXPECT_TRUE(h.mayContribute(std::nextafter(0.7f, 0.0f), 1.0f));
    // Valid up to the top: [1, 1] contributes.
    EXPECT_TRUE(BlendFunction(0.5f, 0.5f, 1.0f, 1.0f).mayContribute(1.0f, 1.0f));
}

// contributesThroughout: hand-computed cases on the built-in distance levels, then against
// brute-force sampling (never claims coverage where some interest in [lo, hi] has weight 0).
TEST(BlendFunctionTest, ContributesThroughoutOnlyWhereTheWeightIsPositiveEverywhere)
{
    const BlendFunction low(0.0f, 0.0f, 0.25f, 0.4f), mid(0.25f, 0.4f, 0.6f, 0.75f),
        high(0.6f, 0.75f, 1.0f, 1.0f);
    // Low: a hard fade-in at 0 admits interest 0; its support ends (open) at 0.4.
    EXPECT_TRUE(low.contributesThroughout(0.0f, 0.3f));
    EXPECT_TRUE(low.contributesThroughout(0.0f, 0.3999f - 1e-3f));
    EXPECT_FALSE(low.contributesThroughout(0.0f, 0.4f));
    EXPECT_FALSE(low.contributesThroughout(0.0f, 0.39995f)); // inside the margin
    // Mid: smooth fade-in at 0.25 is 0 at 0.25 itself.
    EXPECT_FALSE(mid.contributesThroughout(0.25f, 0.5f));
    EXPECT_TRUE(mid.contributesThroughout(0.26f, 0.74f));
    EXPECT_FALSE(mid.contributesThroughout(0.3f, 0.8f));
    // High: fade-out at 1 keeps the top of the axis.
    EXPECT_TRUE(high.contributesThroughout(0.61f, 1.0f));
    EXPECT_FALSE(high.contributesThroughout(0.5f, 1.0f));
    // Degenerate intervals.
    EXPECT_FALSE(mid.contributesThroughout(0.5f, 0.4f));
    EXPECT_FALSE(mid.contributesThroughout(kNaN, 0.5f));
    EXPECT_FALSE(mid.contributesThroughout(0.5f, kNaN));

    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (const BlendFunction& f : {low, mid, high, BlendFunction(0.3f, 0.3f, 0.7f, 0.7f)})
        for (int i = 0; i < 2000; ++i)
        {
            float lo = u(rng), hi = u(rng);
            if (hi < lo) std::swap(lo, hi);
            if (!f.contributesThroughout(lo, hi)) continue;
            for (int k = 0; k <= 200; ++k)
            {
                const float x = lo + (hi - lo) * float(k) / 200.0f;
                ASSERT_GT(f.weight(x), 0.0f) << "[" << lo << ", " << hi << "] at " << x;
            }
        }
}
