/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/palette/KMeansPalette>
#include <osgLoA/palette/PaletteHierarchy>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>

namespace osgLoA
{

namespace
{
double sq(const osg::Vec3d& a, const osg::Vec3d& b)
{
    const osg::Vec3d d = a - b;
    return d * d;
}

/** Index i with prefix sum of p crossing u * total (p >= 0); the last positive one on rounding. */
std::size_t sample(const std::vector<double>& p, double total, double u)
{
    const double target = u * total;
    double acc = 0.0;
    std::size_t lastPositive = 0;
    for (std::size_t i = 0; i < p.size(); ++i)
    {
        if (p[i] <= 0.0) continue;
        acc += p[i];
        lastPositive = i;
        if (acc > target) return i;
    }
    return lastPositive;
}
} // namespace

KMeansPalette::Result KMeansPalette::cluster(const std::vector<WeightedColor>& colors, unsigned k,
                                             std::uint64_t seed)
{
    // The same input checks as the hierarchy (empty table, weights, channels).
    {
        osg::ref_ptr<PaletteHierarchy> check = new PaletteHierarchy;
        if (colors.empty()) throw std::invalid_argument("colors: the table is empty");
        check->setColors(colors);
    }
    const std::size_t n = colors.size();
    if (k < 1 || k > n)
        throw std::invalid_argument("k: " + std::to_string(k) + " is not in [1, " + std::to_string(n) + "]");
    std::vector<osg::Vec3d> lab(n);
    std::vector<double> w(n);
    for (std::size_t i = 0; i < n; ++i)
    {
        lab[i] = osg::Vec3d(WeightedColor::toLab(colors[i].rgb));
        w[i] = colors[i].weight;
    }
    std::mt19937_64 rng(seed);
    auto uniform = [&]() { return double(rng() >> 11) * (1.0 / 9007199254740992.0); };

    // k-means++ seeding.
    Result r;
    std::vector<double> d2(n, std::numeric_limits<double>::infinity()), p(n);
    std::vector<char> chosen(n, 0);
    double total = 0.0;
    for (double wi : w)
        total += wi;
    std::size_t first = sample(w, total, uniform());
    r.lab.push_back(lab[first]);
    chosen[first] = 1;
    while (r.lab.size() < k)
    {
        double sum = 0.0;
        for (std::size_t i = 0; i < n; ++i)
        {
            d2[i] = std::min(d2[i], sq(lab[i], r.lab.back()));
            p[i] = w[i] * d2[i];
            sum += p[i];
        }
        std::size_t next = 0;
        if (sum > 0.0)
            next = sample(p, sum, uniform());
        else
            while (chosen[next])
                ++next;
        chosen[next] = 1;
        r.lab.push_back(lab[next]);
    }

    // Lloyd iterations.
    r.assignment.assign(n, ~0u);
    std::vector<osg::Vec3d> sumLab(k);
    std::vector<double> sumW(k);
    for (r.iterations = 0; r.iterations < MAX_ITERATIONS; ++r.iterations)
    {
        bool changed = false;
        std::vector<double> nearest(n);
        for (std::size_t i = 0; i < n; ++i)
        {
            unsigned best = 0;
            double bestD = sq(lab[i], r.lab[0]);
            for (unsigned c = 1; c < k; ++c)
            {
                const double d = sq(lab[i], r.lab[c]);
                if (d < bestD)
                {
                    bestD = d;
                    best = c;
                }
            }
            nearest[i] = bestD;
            if (r.assignment[i] != best) changed = true;
            r.assignment[i] = best;
        }
        if (!changed) break;
        std::fill(sumLab.begin(), sumLab.end(), osg::Vec3d());
        std::fill(sumW.begin(), sumW.end(), 0.0);
        for (std::size_t i = 0; i < n; ++i)
        {
            sumLab[r.assignment[i]] += lab[i] * w[i];
            sumW[r.assignment[i]] += w[i];
        }
        for (unsigned c = 0; c < k; ++c)
        {
            if (sumW[c] > 0.0)
            {
                r.lab[c] = sumLab[c] / sumW[c];
                continue;
            }
            std::size_t far = 0;
            for (std::size_t i = 1; i < n; ++i)
                if (w[i] * nearest[i] > w[far] * nearest[far]) far = i;
            r.lab[c] = lab[far];
            nearest[far] = 0.0;
        }
    }
    r.colors.resize(k);
    std::vector<double> weight(k, 0.0);
    double errSum = 0.0;
    for (std::size_t i = 0; i < n; ++i)
    {
        weight[r.assignment[i]] += w[i];
        errSum += w[i] * WeightedColor::deltaE(lab[i], r.lab[r.assignment[i]]);
    }
    r.error = errSum / total;
    for (unsigned c = 0; c < k; ++c)
        r.colors[c] = WeightedColor(WeightedColor::fromLab(osg::Vec3f(r.lab[c])), weight[c]);
    return r;
}

std::vector<WeightedColor> KMeansPalette::palette(const std::vector<WeightedColor>& colors, unsigned k,
                                                  std::uint64_t seed)
{
    return cluster(colors, k, seed).colors;
}

double KMeansPalette::error(const std::vector<WeightedColor>& colors, unsigned k, std::uint64_t seed)
{
    return cluster(colors, k, seed).error;
}

} // namespace osgLoA
