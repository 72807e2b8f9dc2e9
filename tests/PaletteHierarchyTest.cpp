// Tests of the colour-palette level of abstraction (paper 003): the hierarchical clustering tree
// (PaletteHierarchy, WARD by nearest-neighbour chain and CENTROID by nearest-neighbour list),
// held against brute-force O(n^3) greedy references; k-means as the paper's comparison; the
// palette texture, its disk cache and the serializer round trip. No GL.
#include <osgLoA/palette/KMeansPalette>
#include <osgLoA/palette/PaletteHierarchy>
#include <osgLoA/palette/PaletteTexture>
#include <osgLoA/palette/WeightedColor>

#include "support/TestSupport.h"

#include <osgDB/ReadFile>
#include <osgDB/WriteFile>

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>

using namespace osgLoA;
typedef PaletteHierarchy::Linkage Linkage;

namespace
{
/** n random sRGB colours, weights uniform in [0.1, 10] (or lognormal(0, 3), spanning about
 *  six orders of magnitude, when wide). */
std::vector<WeightedColor> randomTable(unsigned n, unsigned seed, bool wide = false)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> c(0.0f, 1.0f);
    std::uniform_real_distribution<double> w(0.1, 10.0);
    std::vector<WeightedColor> t;
    for (unsigned i = 0; i < n; ++i)
    {
        const float r = c(rng), g = c(rng), b = c(rng);
        t.push_back(WeightedColor(osg::Vec3f(r, g, b), w(rng)));
    }
    if (wide)
    {
        std::lognormal_distribution<double> lw(0.0, 3.0);
        for (WeightedColor& entry : t)
            entry.weight = lw(rng);
    }
    return t;
}

/** A grey whose Lab is (L, ~0, ~0). */
WeightedColor grey(float L, double weight)
{
    return WeightedColor(WeightedColor::fromLab(osg::Vec3f(L, 0.0f, 0.0f)), weight);
}

struct RefMerge
{
    unsigned first, second;
    osg::Vec3d lab;
    double weight;
};

/** Brute-force greedy agglomeration, O(n^3): at every step every pair of active clusters is
 *  scored and the smallest score merged (ties: smaller first, then smaller second number). */
std::vector<RefMerge> bruteForce(const std::vector<WeightedColor>& colors, Linkage linkage)
{
    struct C
    {
        unsigned id;
        osg::Vec3d lab;
        double w;
    };
    std::vector<C> active;
    for (unsigned i = 0; i < colors.size(); ++i)
        active.push_back({i, osg::Vec3d(WeightedColor::toLab(colors[i].rgb)), colors[i].weight});
    std::vector<RefMerge> out;
    unsigned next = unsigned(colors.size());
    while (active.size() > 1)
    {
        double best = std::numeric_limits<double>::infinity();
        std::size_t bi = 0, bj = 0;
        for (std::size_t i = 0; i < active.size(); ++i)
            for (std::size_t j = 0; j < active.size(); ++j)
            {
                if (active[i].id >= active[j].id) continue;
                const osg::Vec3d d = active[i].lab - active[j].lab;
                const double sq = d * d;
                const double score = linkage == PaletteHierarchy::WARD
                                         ? active[i].w * active[j].w / (active[i].w + active[j].w) * sq
                                         : sq;
                const bool better =
                    score < best ||
                    (score == best && (active[i].id < active[bi].id ||
                                       (active[i].id == active[bi].id && active[j].id < active[bj].id)));
                if (better)
                {
                    best = score;
                    bi = i;
                    bj = j;
                }
            }
        const C a = active[bi], b = active[bj];
        RefMerge m{a.id, b.id, (a.lab * a.w + b.lab * b.w) / (a.w + b.w), a.w + b.w};
        out.push_back(m);
        active.erase(active.begin() + std::max(bi, bj));
        active.erase(active.begin() + std::min(bi, bj));
        active.push_back({next++, m.lab, m.weight});
    }
    return out;
}

void expectSameAsBruteForce(const std::vector<WeightedColor>& colors, Linkage linkage,
                            const std::string& what)
{
    osg::ref_ptr<PaletteHierarchy> h = PaletteHierarchy::build(colors, linkage);
    const std::vector<RefMerge> ref = bruteForce(colors, linkage);
    ASSERT_EQ(h->merges().size(), ref.size());
    for (std::size_t k = 0; k < ref.size(); ++k)
    {
        ASSERT_EQ(h->merges()[k].first, ref[k].first) << what << " merge " << k;
        ASSERT_EQ(h->merges()[k].second, ref[k].second) << what << " merge " << k;
        EXPECT_NEAR((h->merges()[k].lab - ref[k].lab).length(), 0.0, 1e-9) << what << " merge " << k;
        EXPECT_NEAR(h->merges()[k].weight, ref[k].weight, 1e-9 * ref[k].weight) << what << " merge " << k;
    }
}

/** Replays h's merges and checks that each joins a globally closest pair under h's linkage at
 *  its step (brute force, O(n^3)); the pair's score may exceed the minimum by 1e-12 relative. */
void expectEveryMergeClosest(const PaletteHierarchy& h, const std::vector<WeightedColor>& colors,
                             const std::string& what)
{
    std::vector<osg::Vec3d> lab;
    std::vector<double> w;
    std::vector<char> alive;
    for (unsigned i = 0; i < colors.size(); ++i)
    {
        lab.push_back(osg::Vec3d(WeightedColor::toLab(colors[i].rgb)));
        w.push_back(colors[i].weight);
        alive.push_back(1);
    }
    auto score = [&](unsigned a, unsigned b)
    {
        const osg::Vec3d d = lab[a] - lab[b];
        return h.getLinkage() == PaletteHierarchy::WARD ? w[a] * w[b] / (w[a] + w[b]) * (d * d) : d * d;
    };
    for (std::size_t k = 0; k < h.merges().size(); ++k)
    {
        const PaletteHierarchy::Merge& m = h.merges()[k];
        double best = std::numeric_limits<double>::infinity();
        for (unsigned i = 0; i < lab.size(); ++i)
            for (unsigned j = i + 1; j < lab.size(); ++j)
                if (alive[i] && alive[j]) best = std::min(best, score(i, j));
        ASSERT_TRUE(alive[m.first] && alive[m.second]) << what << " merge " << k;
        ASSERT_LE(score(m.first, m.second), best * (1.0 + 1e-12)) << what << " merge " << k;
        alive[m.first] = alive[m.second] = 0;
        lab.push_back(m.lab);
        w.push_back(m.weight);
        alive.push_back(1);
    }
}

/** Checks every level of h against its definition. */
void checkInvariants(const PaletteHierarchy& h, const std::vector<WeightedColor>& colors)
{
    const unsigned n = unsigned(colors.size());
    double total = 0.0;
    for (const WeightedColor& c : colors)
        total += c.weight;
    std::vector<unsigned> finer;
    for (unsigned k = n; k >= 1; --k)
    {
        const PaletteHierarchy::Colors pal = h.palette(k);
        const std::vector<osg::Vec3d> lab = h.paletteLab(k);
        const std::vector<unsigned> assign = h.assignment(k);
        ASSERT_EQ(pal.size(), k);
        ASSERT_EQ(lab.size(), k);
        ASSERT_EQ(assign.size(), n);
        // Members' weighted mean and weight, recomputed from the originals.
        std::vector<osg::Vec3d> sum(k);
        std::vector<double> weight(k, 0.0);
        for (unsigned i = 0; i < n; ++i)
        {
            ASSERT_LT(assign[i], k);
            sum[assign[i]] += h.labOf(i) * colors[i].weight;
            weight[assign[i]] += colors[i].weight;
        }
        double palTotal = 0.0;
        for (unsigned c = 0; c < k; ++c)
        {
            ASSERT_GT(weight[c], 0.0) << "level " << k << " cluster " << c << " has no member";
            EXPECT_LT((sum[c] / weight[c] - lab[c]).length(), 1e-4) << "level " << k << " cluster " << c;
            EXPECT_NEAR(pal[c].weight, weight[c], 1e-9 * total);
            const osg::Vec3f rgb = WeightedColor::fromLab(osg::Vec3f(lab[c]));
            EXPECT_EQ(pal[c].rgb, rgb);
            palTotal += pal[c].weight;
        }
        EXPECT_NEAR(palTotal, total, 1e-9 * total) << "level " << k;
        // Nesting: clusters of level k are unions of clusters of level k + 1, and exactly two
        // of level k + 1 joined.
        if (!finer.empty())
        {
            std::vector<unsigned> coarseOf(k + 1, ~0u);
            for (unsigned i = 0; i < n; ++i)
            {
                unsigned& c = coarseOf[finer[i]];
                if (c == ~0u) c = assign[i];
                ASSERT_EQ(c, assign[i]) << "level " << k << " splits a cluster of level " << k + 1;
            }
        }
        finer = assign;
    }
}
} // namespace

TEST(PaletteHierarchyTest, RefusesBadInput)
{
    auto message = [](const std::vector<WeightedColor>& t)
    {
        try
        {
            PaletteHierarchy::build(t);
        }
        catch (const std::invalid_argument& e)
        {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_EQ(message({}), "colors: the table is empty");
    std::vector<WeightedColor> t = randomTable(5, 1);
    t[3].weight = 0.0;
    EXPECT_EQ(message(t), "colors[3]: weight 0 must be finite and > 0");
    t[3].weight = std::numeric_limits<double>::infinity();
    EXPECT_EQ(message(t), "colors[3]: weight inf must be finite and > 0");
    t[3].weight = 1.0;
    t[2].rgb[1] = std::nanf("");
    EXPECT_NE(message(t).find("colors[2]: channel 1"), std::string::npos) << message(t);

    osg::ref_ptr<PaletteHierarchy> one =
        PaletteHierarchy::build({WeightedColor(osg::Vec3f(0.2f, 0.4f, 0.6f), 3.0)});
    EXPECT_EQ(one->numColors(), 1u);
    EXPECT_TRUE(one->merges().empty());
    ASSERT_EQ(one->palette(1).size(), 1u);
    EXPECT_NEAR((one->palette(1)[0].rgb - osg::Vec3f(0.2f, 0.4f, 0.6f)).length(), 0.0f, 1e-4f);
    EXPECT_EQ(one->error(1), 0.0);
    EXPECT_THROW(one->palette(0), std::invalid_argument);
    EXPECT_THROW(one->palette(2), std::invalid_argument);
}

TEST(PaletteHierarchyTest, InvariantsOnRandomTables)
{
    for (Linkage linkage : {PaletteHierarchy::WARD, PaletteHierarchy::CENTROID})
    {
        const std::vector<WeightedColor> t = randomTable(200, 7);
        osg::ref_ptr<PaletteHierarchy> h = PaletteHierarchy::build(t, linkage);
        ASSERT_EQ(h->merges().size(), 199u);
        SCOPED_TRACE(PaletteHierarchy::toString(linkage));
        checkInvariants(*h, t);
        // palette(n) is the table itself (ordered by smallest member = identity), up to Lab.
        const std::vector<unsigned> identity = h->assignment(200);
        for (unsigned i = 0; i < 200; ++i)
            EXPECT_EQ(identity[i], i);
        // WARD's distances are monotone (reducible); CENTROID's may invert. Report both.
        unsigned inversions = 0;
        for (std::size_t k = 1; k < h->merges().size(); ++k)
            if (h->merges()[k].distance < h->merges()[k - 1].distance) ++inversions;
        if (linkage == PaletteHierarchy::WARD)
        {
            EXPECT_EQ(inversions, 0u);
        }
        std::printf("[ info ] %s n=200: %u merge-distance inversions\n", PaletteHierarchy::toString(linkage),
                    inversions);
    }
}

// Four greys on the L* axis, two heavy close ones and two light ones further apart:
//   0: L 20 w 100   1: L 30 w 100   2: L 50 w 1   3: L 62 w 1
// CENTROID (|ca - cb|): d01 = 10 < d23 = 12 < d12 = 20 -> merge 0+1 -> 4 = L 25 (w 200);
//   then d(4,2) = 25 > d23 = 12 -> 2+3 -> 5 = L 56 (w 2); then 4+5 -> 6 = L (5000+112)/202
//   = 25.3069 (w 202).
// WARD (wa wb / (wa + wb) d^2): 01: 50 * 100 = 5000; 12: 100/101 * 400 = 396.04; 23: 0.5 * 144 =
//   72 -> 2+3 -> 4 = L 56 (w 2); then 1-4: 200/102 * 26^2 = 1325.5 < 01 = 5000 -> 1+4 -> 5 =
//   L (3000 + 112)/102 = 30.5098 (w 102); then 0+5 -> 6 = L (2000 + 3112)/202 = 25.3069 at
//   100 * 102 / 202 * 10.5098^2 = 5577.5.
TEST(PaletteHierarchyTest, HandCaseWardAndCentroidDiffer)
{
    const std::vector<WeightedColor> t = {grey(20, 100), grey(30, 100), grey(50, 1), grey(62, 1)};
    for (const WeightedColor& c : t) // the greys are on the L* axis to float precision
        EXPECT_LT(std::hypot(WeightedColor::toLab(c.rgb)[1], WeightedColor::toLab(c.rgb)[2]), 2e-3);
    struct Expected
    {
        unsigned first, second;
        double L, weight, distance;
    };
    const Expected centroid[3] = {
        {0, 1, 25.0, 200, 10.0}, {2, 3, 56.0, 2, 12.0}, {4, 5, 25.3069, 202, 30.99}};
    const Expected ward[3] = {{2, 3, 56.0, 2, 72.0},
                              {1, 4, 30.5098, 102, 1325.49},
                              {0, 5, 25.3069, 202, 100.0 * 102 / 202 * 10.5098 * 10.5098}};
    for (Linkage linkage : {PaletteHierarchy::WARD, PaletteHierarchy::CENTROID})
    {
        osg::ref_ptr<PaletteHierarchy> h = PaletteHierarchy::build(t, linkage);
        const Expected* e = linkage == PaletteHierarchy::WARD ? ward : centroid;
        ASSERT_EQ(h->merges().size(), 3u);
        for (int k = 0; k < 3; ++k)
        {
            SCOPED_TRACE(std::string(PaletteHierarchy::toString(linkage)) + " merge " + std::to_string(k));
            const PaletteHierarchy::Merge& m = h->merges()[k];
            EXPECT_EQ(m.first, e[k].first);
            EXPECT_EQ(m.second, e[k].second);
            EXPECT_NEAR(m.lab.x(), e[k].L, 2e-3); // the greys' L* are within 1e-3 of nominal
            EXPECT_NEAR(m.weight, e[k].weight, 1e-12);
            EXPECT_NEAR(m.distance, e[k].distance, 0.02 * e[k].distance);
        }
    }
    // The difference shows at level 3: CENTROID keeps {0+1, 2, 3}, WARD keeps {0, 1, 2+3}.
    EXPECT_EQ(PaletteHierarchy::build(t, PaletteHierarchy::CENTROID)->assignment(3),
              (std::vector<unsigned>{0, 0, 1, 2}));
    EXPECT_EQ(PaletteHierarchy::build(t, PaletteHierarchy::WARD)->assignment(3),
              (std::vector<unsigned>{0, 1, 2, 2}));
}

TEST(PaletteHierarchyTest, WardNNChainEqualsBruteForceGreedy)
{
    for (unsigned seed : {1u, 2u, 3u, 4u, 5u})
        expectSameAsBruteForce(randomTable(60, seed), PaletteHierarchy::WARD,
                               "ward seed " + std::to_string(seed));
}

TEST(PaletteHierarchyTest, CentroidEqualsBruteForceGreedy)
{
    for (unsigned seed : {1u, 2u, 3u, 4u, 5u})
    {
        expectSameAsBruteForce(randomTable(60, seed), PaletteHierarchy::CENTROID,
                               "centroid seed " + std::to_string(seed));
        expectSameAsBruteForce(randomTable(60, seed, true), PaletteHierarchy::CENTROID,
                               "centroid wide weights seed " + std::to_string(seed));
    }
}

// Many exact ties: 60 colours drawn from 6 distinct ones with weights 1 or 2.
TEST(PaletteHierarchyTest, TiesBreakTowardsLowerNumbers)
{
    std::vector<WeightedColor> t;
    const osg::Vec3f base[6] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}, {0.5f, 0.5f, 0.5f}, {0, 0, 0}};
    for (unsigned i = 0; i < 60; ++i)
        t.push_back(WeightedColor(base[(i * 7) % 6], 1.0 + double(i % 2)));
    expectSameAsBruteForce(t, PaletteHierarchy::CENTROID, "centroid ties");
    expectSameAsBruteForce(t, PaletteHierarchy::WARD, "ward ties");
    // Heavier ties: 150 colours on a 4-level-per-channel grid (many duplicates) with integer
    // weights. CENTROID still equals the brute-force greedy sequence. WARD's NN-chain does not
    // (its chain prefers the previous element among equal distances; measured: the sequences
    // part at merge 5 for this table), but every one of its merges is a closest pair.
    std::vector<WeightedColor> grid = randomTable(150, 100, true);
    for (WeightedColor& c : grid)
    {
        for (int ch = 0; ch < 3; ++ch)
            c.rgb[ch] = std::round(c.rgb[ch] * 3.0f) / 3.0f;
        c.weight = std::round(c.weight) + 1.0;
    }
    expectSameAsBruteForce(grid, PaletteHierarchy::CENTROID, "centroid grid");
    expectEveryMergeClosest(*PaletteHierarchy::build(grid, PaletteHierarchy::WARD), grid, "ward grid");
    expectEveryMergeClosest(*PaletteHierarchy::build(grid, PaletteHierarchy::CENTROID), grid,
                            "centroid grid");
    // Identical colours: (0,1) -> 4, (2,3) -> 5, (4,5) -> 6 for both.
    const std::vector<WeightedColor> same(4, WeightedColor(osg::Vec3f(0.3f, 0.3f, 0.3f), 1.0));
    for (Linkage linkage : {PaletteHierarchy::WARD, PaletteHierarchy::CENTROID})
    {
        osg::ref_ptr<PaletteHierarchy> h = PaletteHierarchy::build(same, linkage);
        EXPECT_EQ(h->merges()[0].first, 0u);
        EXPECT_EQ(h->merges()[0].second, 1u);
        EXPECT_EQ(h->merges()[1].first, 2u);
        EXPECT_EQ(h->merges()[1].second, 3u);
        EXPECT_EQ(h->merges()[2].first, 4u);
        EXPECT_EQ(h->merges()[2].second, 5u);
    }
}

// error(k) is not monotone for hierarchies in general; what holds: error(n) = 0 and error(1) is
// the weighted mean distance to the global weighted mean.
TEST(PaletteHierarchyTest, ErrorAtTheEnds)
{
    const std::vector<WeightedColor> t = randomTable(200, 11);
    osg::Vec3d mean;
    double total = 0.0;
    for (const WeightedColor& c : t)
    {
        mean += osg::Vec3d(WeightedColor::toLab(c.rgb)) * c.weight;
        total += c.weight;
    }
    mean /= total;
    double expected1 = 0.0;
    for (const WeightedColor& c : t)
        expected1 += c.weight * (osg::Vec3d(WeightedColor::toLab(c.rgb)) - mean).length();
    expected1 /= total;
    for (Linkage linkage : {PaletteHierarchy::WARD, PaletteHierarchy::CENTROID})
    {
        osg::ref_ptr<PaletteHierarchy> h = PaletteHierarchy::build(t, linkage);
        EXPECT_EQ(h->error(200), 0.0);
        EXPECT_NEAR(h->error(1), expected1, 1e-9 * expected1);
        unsigned rises = 0;
        for (unsigned k = 1; k < 200; ++k)
            if (h->error(k + 1) > h->error(k)) ++rises;
        std::printf("[ info ] %s: error(1) = %.4f, error(16) = %.4f, error(64) = %.4f; error rises with k at "
                    "%u of 199 steps\n",
                    PaletteHierarchy::toString(linkage), h->error(1), h->error(16), h->error(64), rises);
    }
}

// Six well-separated blobs of 40 colours each (jitter +-0.03 around six sRGB colours).
TEST(PaletteHierarchyTest, KMeansComparison)
{
    const osg::Vec3f centre[6] = {{0.9f, 0.1f, 0.1f}, {0.1f, 0.8f, 0.2f}, {0.1f, 0.2f, 0.9f},
                                  {0.9f, 0.9f, 0.2f}, {0.5f, 0.5f, 0.5f}, {0.05f, 0.05f, 0.05f}};
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> jitter(-0.03f, 0.03f);
    std::uniform_real_distribution<double> w(0.5, 5.0);
    std::vector<WeightedColor> t;
    std::vector<unsigned> blob;
    for (unsigned b = 0; b < 6; ++b)
        for (unsigned i = 0; i < 40; ++i)
        {
            t.push_back(WeightedColor(centre[b] + osg::Vec3f(jitter(rng), jitter(rng), jitter(rng)), w(rng)));
            blob.push_back(b);
        }
    const KMeansPalette::Result r = KMeansPalette::cluster(t, 6, 42);
    ASSERT_EQ(r.colors.size(), 6u);
    ASSERT_EQ(r.lab.size(), 6u);
    std::printf("[ info ] k-means k=6: %u iterations\n", r.iterations);
    EXPECT_LT(r.iterations, KMeansPalette::MAX_ITERATIONS);
    // Each k-means cluster is exactly one blob.
    std::vector<unsigned> blobOf(6, ~0u);
    for (std::size_t i = 0; i < t.size(); ++i)
    {
        unsigned& b = blobOf[r.assignment[i]];
        if (b == ~0u) b = blob[i];
        EXPECT_EQ(b, blob[i]);
    }
    // Deterministic for a seed.
    EXPECT_EQ(KMeansPalette::cluster(t, 6, 42).assignment, r.assignment);
    for (Linkage linkage : {PaletteHierarchy::WARD, PaletteHierarchy::CENTROID})
    {
        osg::ref_ptr<PaletteHierarchy> h = PaletteHierarchy::build(t, linkage);
        // At k = 6 both find the blobs, so the centres are the same means: equal errors.
        EXPECT_LE(r.error, h->error(6) + 1e-9) << PaletteHierarchy::toString(linkage);
        std::printf("[ info ] %s vs k-means error: k=6 %.4f / %.4f", PaletteHierarchy::toString(linkage),
                    h->error(6), r.error);
        for (unsigned k : {3u, 12u, 24u})
            std::printf(", k=%u %.4f / %.4f", k, h->error(k), KMeansPalette::error(t, k, 42));
        std::printf("\n");
    }
    EXPECT_THROW(KMeansPalette::cluster(t, 0, 1), std::invalid_argument);
    EXPECT_THROW(KMeansPalette::cluster(t, 241, 1), std::invalid_argument);
    // Fewer distinct colours than k: still k centres, all colours at distance 0.
    const std::vector<WeightedColor> two = {WeightedColor(osg::Vec3f(1, 0, 0), 1),
                                            WeightedColor(osg::Vec3f(1, 0, 0), 2),
                                            WeightedColor(osg::Vec3f(0, 0, 1), 1)};
    const KMeansPalette::Result r3 = KMeansPalette::cluster(two, 3, 1);
    EXPECT_EQ(r3.colors.size(), 3u);
    EXPECT_EQ(r3.error, 0.0);
}

// Scale: a table of 20,000 colours. The NN-chain holds O(n) state (5 arrays of n doubles or
// ints plus the chain), no n x n matrix: 20,000^2 doubles would be 3.2 GB.
TEST(PaletteHierarchyTest, WardScalesToTwentyThousandColours)
{
    const std::vector<WeightedColor> t = randomTable(20000, 99);
    const auto t0 = std::chrono::steady_clock::now();
    osg::ref_ptr<PaletteHierarchy> h = PaletteHierarchy::build(t, PaletteHierarchy::WARD);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("[ info ] WARD n=20000: %.2f s\n", s);
    EXPECT_LT(s, 20.0);
    ASSERT_EQ(h->merges().size(), 19999u);
    double total = 0.0;
    for (const WeightedColor& c : t)
        total += c.weight;
    EXPECT_NEAR(h->merges().back().weight, total, 1e-9 * total);
    for (std::size_t k = 1; k < h->merges().size(); ++k)
        ASSERT_GE(h->merges()[k].distance, h->merges()[k - 1].distance) << k;
    EXPECT_EQ(h->palette(256).size(), 256u);

    const std::vector<WeightedColor> t5 = randomTable(5000, 98);
    const auto c0 = std::chrono::steady_clock::now();
    osg::ref_ptr<PaletteHierarchy> c = PaletteHierarchy::build(t5, PaletteHierarchy::CENTROID);
    const double cs = std::chrono::duration<double>(std::chrono::steady_clock::now() - c0).count();
    std::printf("[ info ] CENTROID n=5000: %.2f s, %lu nearest-neighbour rescans (%.2f per merge)\n", cs,
                PaletteHierarchy::lastRescans(), double(PaletteHierarchy::lastRescans()) / 4999.0);
    EXPECT_EQ(c->merges().size(), 4999u);
}

TEST(PaletteHierarchyTest, PaletteTextureLayout)
{
    const std::vector<WeightedColor> t = randomTable(10, 5);
    osg::ref_ptr<PaletteHierarchy> h = PaletteHierarchy::build(t);
    EXPECT_THROW(PaletteTexture::createImage(*h, 0), std::invalid_argument);
    osg::ref_ptr<osg::Image> full = PaletteTexture::createImage(*h);
    EXPECT_EQ(full->s(), 10);
    EXPECT_EQ(full->t(), 10);
    osg::ref_ptr<osg::Image> img = PaletteTexture::createImage(*h, 6);
    ASSERT_EQ(img->s(), 6);
    ASSERT_EQ(img->t(), 6);
    EXPECT_EQ(img->getPixelFormat(), GLenum(GL_RGBA));
    EXPECT_EQ(img->getDataType(), GLenum(GL_UNSIGNED_BYTE));
    for (unsigned k = 1; k <= 6; ++k)
    {
        std::vector<osg::Vec3d> lab = h->paletteLab(k);
        std::sort(lab.begin(), lab.end(),
                  [](const osg::Vec3d& a, const osg::Vec3d& b) { return a.x() < b.x(); });
        const unsigned char* row = img->data(0, int(k - 1));
        for (unsigned x = 0; x < 6; ++x)
        {
            const osg::Vec3f rgb = WeightedColor::fromLab(osg::Vec3f(lab[std::min(x, k - 1)]));
            for (int ch = 0; ch < 3; ++ch)
                EXPECT_EQ(int(row[4 * x + ch]), int(std::lround(rgb[ch] * 255.0f)))
                    << "k " << k << " x " << x;
            EXPECT_EQ(int(row[4 * x + 3]), 255);
        }
    }
    // Row 0 is the global weighted mean.
    osg::Vec3d mean;
    double total = 0.0;
    for (unsigned i = 0; i < 10; ++i)
    {
        mean += h->labOf(i) * t[i].weight;
        total += t[i].weight;
    }
    const osg::Vec3f rgb0 = WeightedColor::fromLab(osg::Vec3f(mean / total));
    EXPECT_NEAR(img->data(0, 0)[0], rgb0[0] * 255.0f, 0.5f + 1e-3f);
}

TEST(PaletteHierarchyTest, TextureCacheRoundTripAndCorruption)
{
    const std::string dir = loatest::freshDirectory("PaletteHierarchyTest-cache");
    const std::vector<WeightedColor> t = randomTable(40, 8);
    osg::ref_ptr<PaletteHierarchy> h = PaletteHierarchy::build(t);
    osg::ref_ptr<osg::Image> img = PaletteTexture::createImage(*h);
    const std::string key = PaletteTexture::contentKey(t, PaletteHierarchy::WARD, 40, "texture bytes");
    EXPECT_FALSE(PaletteTexture::loadCached(dir, key).valid()); // nothing yet
    PaletteTexture::saveCached(dir, key, *img);
    const std::string path = PaletteTexture::cachePath(dir, key);
    EXPECT_EQ(path.size(), dir.size() + 1 + 32 + 7); // 32 hex digits + ".loapal"
    osg::ref_ptr<osg::Image> back = PaletteTexture::loadCached(dir, key);
    ASSERT_TRUE(back.valid());
    ASSERT_EQ(back->s(), 40);
    ASSERT_EQ(back->t(), 40);
    EXPECT_EQ(std::memcmp(back->data(), img->data(), 40 * 40 * 4), 0);
    // Another key (other linkage) is another file: a miss.
    EXPECT_FALSE(PaletteTexture::loadCached(
                     dir, PaletteTexture::contentKey(t, PaletteHierarchy::CENTROID, 40, "texture bytes"))
                     .valid());
    const std::string good = loatest::fileBytes(path);
    ASSERT_EQ(good.size(), 32u + 40u * 40u * 4u + 16u);
    // Every single-byte change at a spread of offsets, and truncations, are misses.
    for (std::size_t at : {std::size_t(0), std::size_t(9), std::size_t(13), std::size_t(20), std::size_t(32),
                           std::size_t(3000), good.size() - 1})
    {
        std::string bad = good;
        bad[at] = char(bad[at] ^ 0x01);
        std::ofstream(path, std::ios::binary | std::ios::trunc) << bad;
        EXPECT_FALSE(PaletteTexture::loadCached(dir, key).valid()) << "flip at " << at;
    }
    for (std::size_t size : {std::size_t(0), std::size_t(10), good.size() / 2, good.size() - 1})
    {
        std::ofstream(path, std::ios::binary | std::ios::trunc) << good.substr(0, size);
        EXPECT_FALSE(PaletteTexture::loadCached(dir, key).valid()) << "truncated to " << size;
    }
    // Rewritten, it reads again.
    PaletteTexture::saveCached(dir, key, *img);
    EXPECT_TRUE(PaletteTexture::loadCached(dir, key).valid());
}

TEST(PaletteHierarchyTest, SerializerRoundTrip)
{
    const std::string dir = loatest::freshDirectory("PaletteHierarchyTest-serializer");
    const std::vector<WeightedColor> t = randomTable(30, 12);
    for (Linkage linkage : {PaletteHierarchy::WARD, PaletteHierarchy::CENTROID})
        for (const char* ext : {"osgt", "osgb"})
        {
            SCOPED_TRACE(std::string(PaletteHierarchy::toString(linkage)) + " " + ext);
            osg::ref_ptr<PaletteHierarchy> h = PaletteHierarchy::build(t, linkage);
            const std::string first = dir + "/first-" + PaletteHierarchy::toString(linkage) + "." + ext,
                              second = dir + "/second-" + PaletteHierarchy::toString(linkage) + "." + ext;
            ASSERT_TRUE(osgDB::writeObjectFile(*h, first));
            osg::ref_ptr<PaletteHierarchy> back =
                dynamic_cast<PaletteHierarchy*>(osgDB::readRefObjectFile(first).get());
            ASSERT_TRUE(back.valid());
            EXPECT_EQ(back->getLinkage(), linkage);
            ASSERT_EQ(back->numColors(), 30u);
            ASSERT_EQ(back->merges().size(), 29u);
            const bool exact = std::string(ext) == "osgb";
            for (std::size_t k = 0; k < 29; ++k)
            {
                EXPECT_EQ(back->merges()[k].first, h->merges()[k].first);
                EXPECT_EQ(back->merges()[k].second, h->merges()[k].second);
                if (exact)
                    EXPECT_EQ(back->merges()[k].lab, h->merges()[k].lab);
                else // text keeps about 6 significant digits of the colours
                    EXPECT_LT((back->merges()[k].lab - h->merges()[k].lab).length(), 1e-3);
            }
            EXPECT_NEAR(back->error(5), h->error(5), exact ? 0.0 : 1e-3);
            ASSERT_TRUE(osgDB::writeObjectFile(*back, second));
            EXPECT_EQ(loatest::fileBytes(first), loatest::fileBytes(second));
        }
    // A merge list that is not a tree fails the read.
    std::string text = loatest::fileBytes(dir + "/first-ward.osgt");
    const std::string::size_type at = text.find("Merges 29");
    ASSERT_NE(at, std::string::npos) << text;
    const std::string::size_type line = text.find('\n', text.find('{', at)) + 1;
    const std::string::size_type end = text.find('\n', line);
    text.replace(line, end - line, "      0 0 1");
    const std::string bad = dir + "/bad.osgt";
    std::ofstream(bad) << text;
    EXPECT_FALSE(osgDB::readRefObjectFile(bad).valid());
}
