/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/palette/PaletteHierarchy>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <queue>
#include <sstream>
#include <stdexcept>

namespace osgLoA
{

namespace
{
unsigned long s_rescans = 0;

/** The active clusters in compact structure-of-arrays form (contiguous scans), with the slot of
 *  each cluster number. Removing moves the last slot into the hole. */
struct ActiveSet
{
    std::vector<double> x, y, z, w;
    std::vector<unsigned> id;
    std::vector<unsigned> slotOf; // by cluster number, 2n - 1 entries

    ActiveSet(const std::vector<osg::Vec3d>& lab, const std::vector<WeightedColor>& colors)
    {
        const std::size_t n = lab.size();
        x.resize(n);
        y.resize(n);
        z.resize(n);
        w.resize(n);
        id.resize(n);
        slotOf.assign(2 * n - 1, ~0u);
        for (std::size_t i = 0; i < n; ++i)
        {
            x[i] = lab[i].x();
            y[i] = lab[i].y();
            z[i] = lab[i].z();
            w[i] = colors[i].weight;
            id[i] = unsigned(i);
            slotOf[i] = unsigned(i);
        }
    }
    std::size_t size() const { return id.size(); }
    void remove(unsigned node)
    {
        const unsigned s = slotOf[node], last = unsigned(id.size() - 1);
        if (s != last)
        {
            x[s] = x[last];
            y[s] = y[last];
            z[s] = z[last];
            w[s] = w[last];
            id[s] = id[last];
            slotOf[id[s]] = s;
        }
        x.pop_back();
        y.pop_back();
        z.pop_back();
        w.pop_back();
        id.pop_back();
        slotOf[node] = ~0u;
    }
    void add(unsigned node, const osg::Vec3d& c, double weight)
    {
        slotOf[node] = unsigned(id.size());
        x.push_back(c.x());
        y.push_back(c.y());
        z.push_back(c.z());
        w.push_back(weight);
        id.push_back(node);
    }
    osg::Vec3d centre(unsigned s) const { return osg::Vec3d(x[s], y[s], z[s]); }
};

/** (wa ca + wb cb) / (wa + wb), symmetric in a and b bit for bit. */
osg::Vec3d mergedColour(const osg::Vec3d& ca, double wa, const osg::Vec3d& cb, double wb)
{
    const double w = wa + wb;
    return osg::Vec3d((wa * ca.x() + wb * cb.x()) / w, (wa * ca.y() + wb * cb.y()) / w,
                      (wa * ca.z() + wb * cb.z()) / w);
}

/** Squared Lab distance between slot s and (cx, cy, cz); symmetric bit for bit. */
inline double squared(const ActiveSet& a, unsigned s, double cx, double cy, double cz)
{
    const double dx = a.x[s] - cx, dy = a.y[s] - cy, dz = a.z[s] - cz;
    return dx * dx + dy * dy + dz * dz;
}

inline double ward(double wa, double wb, double sq)
{
    return (wa * wb) / (wa + wb) * sq;
}

/** Generated merge of the NN-chain, in the chain's order. */
struct Generated
{
    unsigned a, b; // generation numbers: originals 0..n-1, generated merge g is n + g
    double height;
    osg::Vec3d lab;
    double weight;
};

PaletteHierarchy::Merges buildWard(const std::vector<osg::Vec3d>& lab,
                                   const std::vector<WeightedColor>& colors)
{
    const unsigned n = unsigned(lab.size());
    ActiveSet act(lab, colors);
    std::vector<Generated> gen;
    gen.reserve(n - 1);
    std::vector<unsigned> chain;
    std::vector<char> inChain(2 * n - 1, 0);
    chain.reserve(n);
    while (act.size() > 1)
    {
        if (chain.empty())
        {
            // Start from the active cluster with the lowest number.
            unsigned lowest = act.id[0];
            for (unsigned s = 1; s < act.size(); ++s)
                lowest = std::min(lowest, act.id[s]);
            chain.push_back(lowest);
            inChain[lowest] = 1;
        }
        const unsigned a = chain.back();
        const unsigned sa = act.slotOf[a];
        const double wa = act.w[sa], ax = act.x[sa], ay = act.y[sa], az = act.z[sa];
        // Nearest neighbour of a; on a tie the chain's previous element wins (needed for the
        // chain to end), then the lower cluster number.
        const unsigned prev = chain.size() >= 2 ? chain[chain.size() - 2] : ~0u;
        unsigned best = ~0u;
        double bestD = std::numeric_limits<double>::infinity();
        if (prev != ~0u)
        {
            best = prev;
            bestD = ward(wa, act.w[act.slotOf[prev]], squared(act, act.slotOf[prev], ax, ay, az));
        }
        const unsigned m = unsigned(act.size());
        for (unsigned s = 0; s < m; ++s)
        {
            if (s == sa) continue;
            // Division-free filter: d < bestD <=> wa wb sq < bestD (wa + wb) in exact arithmetic;
            // the 1e-12 margin (far above the few ulps of rounding) keeps every candidate that
            // the exact comparison below could accept, ties included.
            const double wb = act.w[s], sq = squared(act, s, ax, ay, az);
            if (wa * wb * sq > bestD * (wa + wb) * (1.0 + 1e-12)) continue;
            const double d = ward(wa, wb, sq);
            if (d < bestD || (d == bestD && best != prev && act.id[s] < best))
            {
                bestD = d;
                best = act.id[s];
            }
        }
        if (best == prev)
        {
            chain.pop_back();
            chain.pop_back();
            inChain[a] = inChain[prev] = 0;
            const unsigned sb = act.slotOf[prev];
            Generated g;
            g.a = std::min(a, prev);
            g.b = std::max(a, prev);
            g.height = bestD;
            g.weight = wa + act.w[sb];
            g.lab = mergedColour(act.centre(sa), wa, act.centre(sb), act.w[sb]);
            act.remove(a);
            act.remove(prev);
            act.add(n + unsigned(gen.size()), g.lab, g.weight);
            gen.push_back(g);
        }
        else if (inChain[best])
        {
            // Only possible through rounding (reducibility holds in exact arithmetic): cut the
            // chain back to best, which then continues the search.
            while (chain.back() != best)
            {
                inChain[chain.back()] = 0;
                chain.pop_back();
            }
        }
        else
        {
            chain.push_back(best);
            inChain[best] = 1;
        }
    }
    // Greedy order. Heights are first made monotone along the tree (a parent never below its
    // children; changes nothing in exact arithmetic). Then the merges are replayed as greedy
    // would pick them: among the merges whose two children exist, the smallest (height,
    // first number, second number), numbers being the greedy numbering built so far. Without
    // ties this is the sort by height; with ties it is greedy's tie-break on this tree.
    const std::size_t count = gen.size();
    std::vector<double> key(count);
    std::vector<unsigned> parentOf(n + count, ~0u);
    for (std::size_t g = 0; g < count; ++g)
    {
        double h = gen[g].height;
        for (unsigned c : {gen[g].a, gen[g].b})
        {
            if (c >= n) h = std::max(h, key[c - n]);
            parentOf[c] = n + unsigned(g);
        }
        key[g] = h;
    }
    std::vector<unsigned> number(n + count, ~0u);
    std::iota(number.begin(), number.begin() + n, 0u);
    struct Ready
    {
        double height;
        unsigned first, second, g;
        bool operator>(const Ready& o) const
        {
            if (height != o.height) return height > o.height;
            if (first != o.first) return first > o.first;
            return second > o.second;
        }
    };
    std::priority_queue<Ready, std::vector<Ready>, std::greater<Ready>> ready;
    auto offer = [&](unsigned g)
    {
        const unsigned p = number[gen[g].a], q = number[gen[g].b];
        if (p != ~0u && q != ~0u) ready.push(Ready{key[g], std::min(p, q), std::max(p, q), g});
    };
    for (std::size_t g = 0; g < count; ++g)
        offer(unsigned(g));
    PaletteHierarchy::Merges merges;
    merges.reserve(count);
    while (!ready.empty())
    {
        const Ready r = ready.top();
        ready.pop();
        const Generated& g = gen[r.g];
        number[n + r.g] = n + unsigned(merges.size());
        PaletteHierarchy::Merge m;
        m.first = r.first;
        m.second = r.second;
        m.distance = g.height;
        m.lab = g.lab;
        m.weight = g.weight;
        merges.push_back(m);
        if (parentOf[n + r.g] != ~0u) offer(parentOf[n + r.g] - n);
    }
    return merges;
}

PaletteHierarchy::Merges buildCentroid(const std::vector<osg::Vec3d>& lab,
                                       const std::vector<WeightedColor>& colors)
{
    const unsigned n = unsigned(lab.size());
    ActiveSet act(lab, colors);
    // Nearest neighbour (cluster number) and squared distance, by slot (moved with the slot).
    std::vector<unsigned> nn(n, ~0u);
    std::vector<double> nnD(n, std::numeric_limits<double>::infinity());
    auto moveSlot = [&](unsigned from, unsigned to)
    {
        nn[to] = nn[from];
        nnD[to] = nnD[from];
    };
    auto rescan = [&](unsigned s)
    {
        const double cx = act.x[s], cy = act.y[s], cz = act.z[s];
        unsigned best = ~0u;
        double bestD = std::numeric_limits<double>::infinity();
        const unsigned m = unsigned(act.size());
        for (unsigned t = 0; t < m; ++t)
        {
            if (t == s) continue;
            const double d = squared(act, t, cx, cy, cz);
            if (d < bestD || (d == bestD && act.id[t] < best))
            {
                bestD = d;
                best = act.id[t];
            }
        }
        nn[s] = best;
        nnD[s] = bestD;
    };
    for (unsigned s = 0; s < n; ++s)
        rescan(s);
    PaletteHierarchy::Merges merges;
    merges.reserve(n - 1);
    std::vector<unsigned> stale;
    unsigned long rescans = 0;
    while (act.size() > 1)
    {
        // The globally closest pair: smallest distance, then smallest first cluster (whose
        // neighbour is already the smallest second one at that distance).
        unsigned bs = 0;
        for (unsigned s = 1; s < act.size(); ++s)
            if (nnD[s] < nnD[bs] || (nnD[s] == nnD[bs] && act.id[s] < act.id[bs])) bs = s;
        const unsigned a = act.id[bs], b = nn[bs];
        const unsigned sa = bs, sb = act.slotOf[b];
        PaletteHierarchy::Merge mg;
        mg.first = std::min(a, b);
        mg.second = std::max(a, b);
        mg.distance = std::sqrt(nnD[bs]);
        mg.weight = act.w[sa] + act.w[sb];
        mg.lab = mergedColour(act.centre(sa), act.w[sa], act.centre(sb), act.w[sb]);
        const unsigned c = n + unsigned(merges.size());
        merges.push_back(mg);
        // Remove a and b (keeping nn/nnD with their slots), add c in the last slot.
        for (unsigned node : {a, b})
        {
            const unsigned s = act.slotOf[node], last = unsigned(act.size() - 1);
            if (s != last) moveSlot(last, s);
            act.remove(node);
        }
        act.add(c, mg.lab, mg.weight);
        const unsigned sc = unsigned(act.size() - 1);
        const double cx = mg.lab.x(), cy = mg.lab.y(), cz = mg.lab.z();
        unsigned bestC = ~0u;
        double bestCD = std::numeric_limits<double>::infinity();
        stale.clear();
        for (unsigned s = 0; s < sc; ++s)
        {
            const double d = squared(act, s, cx, cy, cz);
            if (d < bestCD || (d == bestCD && act.id[s] < bestC))
            {
                bestCD = d;
                bestC = act.id[s];
            }
            if (nn[s] == a || nn[s] == b)
                stale.push_back(s);
            else if (d < nnD[s]) // a tie keeps the old, lower-numbered neighbour
            {
                nn[s] = c;
                nnD[s] = d;
            }
        }
        nn[sc] = bestC;
        nnD[sc] = bestCD;
        for (unsigned s : stale)
            rescan(s);
        rescans += stale.size();
    }
    s_rescans = rescans;
    return merges;
}

void checkColors(const PaletteHierarchy::Colors& colors)
{
    if (colors.empty()) throw std::invalid_argument("colors: the table is empty");
    if (colors.size() > (std::numeric_limits<unsigned>::max() >> 2))
        throw std::invalid_argument("colors: the table has too many entries (" +
                                    std::to_string(colors.size()) + ")");
    for (std::size_t i = 0; i < colors.size(); ++i)
    {
        const WeightedColor& c = colors[i];
        if (!(std::isfinite(c.weight) && c.weight > 0.0))
        {
            std::ostringstream s;
            s << "colors[" << i << "]: weight " << c.weight << " must be finite and > 0";
            throw std::invalid_argument(s.str());
        }
        for (int ch = 0; ch < 3; ++ch)
            if (!std::isfinite(c.rgb[ch]))
            {
                std::ostringstream s;
                s << "colors[" << i << "]: channel " << ch << " is " << c.rgb[ch] << "; it must be finite";
                throw std::invalid_argument(s.str());
            }
    }
}
} // namespace

PaletteHierarchy::PaletteHierarchy(const PaletteHierarchy& other, const osg::CopyOp& copyop)
    : osg::Object(other, copyop), _linkage(other._linkage), _colors(other._colors), _lab(other._lab),
      _merges(other._merges)
{
}

const char* PaletteHierarchy::toString(Linkage linkage)
{
    switch (linkage)
    {
    case WARD:
        return "ward";
    case CENTROID:
        return "centroid";
    }
    return "unknown";
}

unsigned long PaletteHierarchy::lastRescans()
{
    return s_rescans;
}

void PaletteHierarchy::setColors(const Colors& colors)
{
    if (!colors.empty()) checkColors(colors);
    _colors = colors;
    _lab.resize(colors.size());
    for (std::size_t i = 0; i < colors.size(); ++i)
        _lab[i] = osg::Vec3d(WeightedColor::toLab(colors[i].rgb));
    _merges.clear();
}

osg::ref_ptr<PaletteHierarchy> PaletteHierarchy::build(const Colors& colors, Linkage linkage)
{
    if (linkage != WARD && linkage != CENTROID)
        throw std::invalid_argument("linkage: unknown value " + std::to_string(int(linkage)));
    checkColors(colors);
    osg::ref_ptr<PaletteHierarchy> h = new PaletteHierarchy;
    h->_linkage = linkage;
    h->setColors(colors);
    if (colors.size() > 1)
        h->_merges = linkage == WARD ? buildWard(h->_lab, colors) : buildCentroid(h->_lab, colors);
    return h;
}

void PaletteHierarchy::setMerges(const Merges& merges)
{
    const std::size_t n = _colors.size();
    if (merges.empty())
    {
        _merges.clear();
        return;
    }
    if (merges.size() != n - 1)
        throw std::invalid_argument("merges: " + std::to_string(merges.size()) + " merges for " +
                                    std::to_string(n) + " colours; a full tree has " +
                                    std::to_string(n == 0 ? 0 : n - 1));
    std::vector<char> used(2 * n - 1, 0);
    Merges out(merges);
    for (std::size_t k = 0; k < out.size(); ++k)
    {
        Merge& m = out[k];
        if (!(m.first < m.second && m.second < n + k) || used[m.first] || used[m.second])
            throw std::invalid_argument("merges[" + std::to_string(k) + "]: clusters " +
                                        std::to_string(m.first) + " and " + std::to_string(m.second) +
                                        " are not two distinct unmerged clusters (first < second < " +
                                        std::to_string(n + k) + ")");
        used[m.first] = used[m.second] = 1;
        auto labOfNode = [&](unsigned node) { return node < n ? _lab[node] : out[node - n].lab; };
        auto weightOfNode = [&](unsigned node)
        { return node < n ? _colors[node].weight : out[node - n].weight; };
        m.weight = weightOfNode(m.first) + weightOfNode(m.second);
        m.lab = mergedColour(labOfNode(m.first), weightOfNode(m.first), labOfNode(m.second),
                             weightOfNode(m.second));
    }
    _merges.swap(out);
}

osg::Vec3d PaletteHierarchy::nodeLab(unsigned node) const
{
    return node < _colors.size() ? _lab[node] : _merges[node - _colors.size()].lab;
}

double PaletteHierarchy::nodeWeight(unsigned node) const
{
    return node < _colors.size() ? _colors[node].weight : _merges[node - _colors.size()].weight;
}

void PaletteHierarchy::level(unsigned k, std::vector<unsigned>& nodes, std::vector<unsigned>* assign) const
{
    const unsigned n = numColors();
    if (n == 0 || k < 1 || k > n || std::size_t(n - k) > _merges.size())
        throw std::invalid_argument(
            "k: level " + std::to_string(k) + " is not in [" +
            std::to_string(n == 0 ? 0 : std::max<std::size_t>(1, n - _merges.size())) + ", " +
            std::to_string(n) + "]");
    const unsigned applied = n - k, total = n + applied;
    std::vector<unsigned> parent(total, ~0u), minMember(total);
    for (unsigned i = 0; i < n; ++i)
        minMember[i] = i;
    for (unsigned m = 0; m < applied; ++m)
    {
        const Merge& mg = _merges[m];
        parent[mg.first] = parent[mg.second] = n + m;
        minMember[n + m] = std::min(minMember[mg.first], minMember[mg.second]);
    }
    nodes.clear();
    for (unsigned v = 0; v < total; ++v)
        if (parent[v] == ~0u) nodes.push_back(v);
    std::sort(nodes.begin(), nodes.end(),
              [&](unsigned p, unsigned q) { return minMember[p] < minMember[q]; });
    if (assign)
    {
        // Parents have larger numbers than children: label from the top down.
        std::vector<unsigned> label(total, ~0u);
        for (unsigned i = 0; i < nodes.size(); ++i)
            label[nodes[i]] = i;
        for (unsigned v = total; v-- > 0;)
            if (label[v] == ~0u) label[v] = label[parent[v]];
        assign->assign(label.begin(), label.begin() + n);
    }
}

std::vector<osg::Vec3d> PaletteHierarchy::paletteLab(unsigned k) const
{
    std::vector<unsigned> nodes;
    level(k, nodes, nullptr);
    std::vector<osg::Vec3d> out;
    out.reserve(nodes.size());
    for (unsigned v : nodes)
        out.push_back(nodeLab(v));
    return out;
}

PaletteHierarchy::Colors PaletteHierarchy::palette(unsigned k) const
{
    std::vector<unsigned> nodes;
    level(k, nodes, nullptr);
    Colors out;
    out.reserve(nodes.size());
    for (unsigned v : nodes)
        out.push_back(WeightedColor(WeightedColor::fromLab(osg::Vec3f(nodeLab(v))), nodeWeight(v)));
    return out;
}

std::vector<unsigned> PaletteHierarchy::assignment(unsigned k) const
{
    std::vector<unsigned> nodes, assign;
    level(k, nodes, &assign);
    return assign;
}

double PaletteHierarchy::error(unsigned k) const
{
    std::vector<unsigned> nodes, assign;
    level(k, nodes, &assign);
    double sum = 0.0, weight = 0.0;
    for (unsigned i = 0; i < numColors(); ++i)
    {
        sum += _colors[i].weight * WeightedColor::deltaE(_lab[i], nodeLab(nodes[assign[i]]));
        weight += _colors[i].weight;
    }
    return sum / weight;
}

} // namespace osgLoA
