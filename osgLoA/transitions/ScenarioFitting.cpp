// ScenarioFitting: library scenarios placed and scaled to the scene they are bound to.
#include <osgLoA/transitions/ScenarioFitting>

#include <osg/Notify>
#include <osg/Transform>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <queue>
#include <set>
#include <sstream>
#include <stdexcept>

namespace osgLoA
{

namespace
{
struct Street
{
    osg::BoundingBoxd box;
    osg::Vec2d centre;
};

std::size_t findRoot(std::vector<std::size_t>& parent, std::size_t x)
{
    while (parent[x] != x)
        x = parent[x] = parent[parent[x]];
    return x;
}

/** Dijkstra from `from` over a graph of points (edges as lists of adjacent vertices, each as
 *  long as the distance between its points); returns distances and predecessors (points.size():
 *  none). */
void shortestPaths(const std::vector<std::vector<std::size_t>>& adjacent,
                   const std::vector<osg::Vec2d>& points, std::size_t from, std::vector<double>& dist,
                   std::vector<std::size_t>& previous)
{
    const double inf = std::numeric_limits<double>::infinity();
    dist.assign(points.size(), inf);
    previous.assign(points.size(), points.size());
    typedef std::pair<double, std::size_t> Item;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
    dist[from] = 0.0;
    queue.push({0.0, from});
    while (!queue.empty())
    {
        const Item top = queue.top();
        queue.pop();
        if (top.first > dist[top.second]) continue;
        for (std::size_t n : adjacent[top.second])
        {
            const double d = top.first + (points[n] - points[top.second]).length();
            if (d < dist[n])
            {
                dist[n] = d;
                previous[n] = top.second;
                queue.push({d, n});
            }
        }
    }
}

/** Douglas-Peucker: keeps the vertices farther than tolerance from the simplified line. */
void simplify(const std::vector<osg::Vec2d>& in, std::size_t a, std::size_t b, double tolerance,
              std::vector<bool>& keep)
{
    if (b <= a + 1) return;
    const osg::Vec2d ab = in[b] - in[a];
    const double len2 = ab.length2();
    double worst = -1.0;
    std::size_t at = a;
    for (std::size_t i = a + 1; i < b; ++i)
    {
        const osg::Vec2d ap = in[i] - in[a];
        const double t = len2 > 0.0 ? std::clamp((ap * ab) / len2, 0.0, 1.0) : 0.0;
        const double d = (ap - ab * t).length();
        if (d > worst)
        {
            worst = d;
            at = i;
        }
    }
    if (worst <= tolerance) return;
    keep[at] = true;
    simplify(in, a, at, tolerance, keep);
    simplify(in, at, b, tolerance, keep);
}

/** The path (two or more vertices) simplified: its end points and the vertices simplify keeps. */
std::vector<osg::Vec2d> simplified(const std::vector<osg::Vec2d>& path, double tolerance)
{
    std::vector<bool> keep(path.size(), false);
    keep.front() = keep.back() = true;
    simplify(path, 0, path.size() - 1, tolerance, keep);
    std::vector<osg::Vec2d> out;
    for (std::size_t i = 0; i < path.size(); ++i)
        if (keep[i]) out.push_back(path[i]);
    return out;
}

const Feature* tallest(const FeatureIndex& index)
{
    const Feature* best = nullptr;
    bool bestLandmark = false;
    double bestHeight = -1.0;
    for (const FeatureIndex::Entry& e : index.entries())
    {
        const Feature& f = *e.feature;
        if (!f.getBound().valid() || (f.getType() != FeatureType::Building && !f.getLandmark())) continue;
        const double h = f.getBound().zMax() - f.getBound().zMin();
        // Landmarks first, then the height.
        if (!best || (f.getLandmark() && !bestLandmark) ||
            (f.getLandmark() == bestLandmark && h > bestHeight))
        {
            best = &f;
            bestLandmark = f.getLandmark();
            bestHeight = h;
        }
    }
    return best;
}

std::string metres(double v)
{
    std::ostringstream s;
    s.precision(v < 10.0 ? 2 : 0);
    s << std::fixed << v;
    return s.str();
}
/** The route along the street network that the features' centre lines form (OSM ways): end
 *  points and vertices within a centimetre are one junction; the longest of the shortest paths
 *  of the largest connected network, found by two Dijkstra sweeps (exact on trees, the usual
 *  approximation of the diameter elsewhere), simplified to the tolerance. Empty when fewer than two
 *  street features have a centre line. */
std::vector<osg::Vec2d> streetNetworkRoute(const FeatureIndex& index, double tolerance, unsigned* features)
{
    std::map<std::pair<long long, long long>, std::size_t> junction;
    std::vector<osg::Vec2d> points;
    std::vector<std::vector<std::size_t>> edges;                            // adjacent junctions
    std::map<std::pair<std::size_t, std::size_t>, std::size_t> edgeFeature; // (from, to) -> feature
    std::vector<const Feature*> owners;
    std::set<const Feature*> seen;
    auto vertex = [&](const osg::Vec2d& p)
    {
        const std::pair<long long, long long> key(std::llround(p.x() * 100.0), std::llround(p.y() * 100.0));
        auto it = junction.find(key);
        if (it != junction.end()) return it->second;
        junction[key] = points.size();
        points.push_back(p);
        edges.emplace_back();
        return points.size() - 1;
    };
    for (const FeatureIndex::Entry& e : index.entries())
    {
        const Feature& f = *e.feature;
        if (f.getType() != FeatureType::Street || f.getCentreline().size() < 2 || !seen.insert(&f).second)
            continue;
        const osg::Matrixd toRoot = osg::computeLocalToWorld(index.pathOf(e));
        std::size_t previous = 0;
        bool first = true;
        for (const osg::Vec2d& c : f.getCentreline())
        {
            const osg::Vec3d w = osg::Vec3d(c.x(), c.y(), 0.0) * toRoot;
            if (!std::isfinite(w.x()) || !std::isfinite(w.y())) continue;
            const std::size_t v = vertex(osg::Vec2d(w.x(), w.y()));
            if (!first && v != previous &&
                edgeFeature.emplace(std::make_pair(previous, v), owners.size()).second)
            {
                edgeFeature.emplace(std::make_pair(v, previous), owners.size());
                edges[previous].push_back(v);
                edges[v].push_back(previous);
            }
            previous = v;
            first = false;
        }
        owners.push_back(&f);
    }
    if (features) *features = 0;
    if (owners.size() < 2 || points.size() < 2) return {};
    std::vector<double> dist;
    std::vector<std::size_t> previous;
    auto sweep = [&](std::size_t from)
    {
        shortestPaths(edges, points, from, dist, previous);
        std::size_t far = from;
        for (std::size_t i = 0; i < points.size(); ++i)
            if (std::isfinite(dist[i]) && dist[i] > dist[far]) far = i;
        return far;
    };
    // The largest network: the one with the most length reachable from its vertices.
    std::vector<int> component(points.size(), -1);
    std::vector<double> length;
    for (std::size_t i = 0; i < points.size(); ++i)
    {
        if (component[i] >= 0) continue;
        const int c = int(length.size());
        length.push_back(0.0);
        std::vector<std::size_t> stack = {i};
        component[i] = c;
        while (!stack.empty())
        {
            const std::size_t v = stack.back();
            stack.pop_back();
            for (std::size_t n : edges[v])
            {
                if (n > v) length[std::size_t(c)] += (points[n] - points[v]).length();
                if (component[n] < 0)
                {
                    component[n] = c;
                    stack.push_back(n);
                }
            }
        }
    }
    const int largest = int(std::max_element(length.begin(), length.end()) - length.begin());
    std::size_t start = 0;
    while (component[start] != largest)
        ++start;
    const std::size_t u = sweep(start);
    const std::size_t v = sweep(u);
    std::vector<osg::Vec2d> path;
    std::set<std::size_t> used;
    for (std::size_t n = v; n != points.size(); n = previous[n])
    {
        path.push_back(points[n]);
        if (previous[n] != points.size()) used.insert(edgeFeature[std::make_pair(n, previous[n])]);
    }
    std::reverse(path.begin(), path.end());
    if (features) *features = unsigned(used.size());
    if (path.size() < 2) return {};
    return simplified(path, tolerance);
}
} // namespace

std::vector<osg::Vec2d> ScenarioFitting::longestStreetChain(const FeatureIndex& index, double tolerance,
                                                            unsigned* features)
{
    // Street features with centre lines (OSM ways): the route follows the network they form.
    // Simplified 20 times finer than the chain of boxes: the line is drawn on the streets
    // (RouteLine) and must stay on them (0.05 % of S, 0.5 m on West Oakland).
    std::vector<osg::Vec2d> route = streetNetworkRoute(index, 0.05 * tolerance, features);
    if (route.size() >= 2) return route;
    std::vector<Street> s;
    std::set<const Feature*> seen; // one Feature may sit on several nodes
    for (const FeatureIndex::Entry& e : index.entries())
    {
        const Feature& f = *e.feature;
        if (f.getType() != FeatureType::Street || !f.getBound().valid() || !seen.insert(&f).second) continue;
        const osg::BoundingBoxf& b = f.getBound();
        s.push_back({osg::BoundingBoxd(osg::Vec3d(b._min), osg::Vec3d(b._max)),
                     osg::Vec2d(b.center().x(), b.center().y())});
    }
    if (features) *features = 0;
    if (s.empty()) return {};
    // The touch graph (ground boxes within tolerance), swept along x.
    std::vector<std::size_t> order(s.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t b) { return s[a].box.xMin() < s[b].box.xMin(); });
    std::vector<std::vector<std::size_t>> adjacent(s.size());
    std::vector<std::size_t> parent(s.size());
    std::iota(parent.begin(), parent.end(), 0);
    for (std::size_t i = 0; i < order.size(); ++i)
        for (std::size_t j = i + 1;
             j < order.size() && s[order[j]].box.xMin() <= s[order[i]].box.xMax() + tolerance; ++j)
        {
            const osg::BoundingBoxd& p = s[order[i]].box;
            const osg::BoundingBoxd& q = s[order[j]].box;
            if (p.yMin() <= q.yMax() + tolerance && q.yMin() <= p.yMax() + tolerance)
            {
                adjacent[order[i]].push_back(order[j]);
                adjacent[order[j]].push_back(order[i]);
                parent[findRoot(parent, order[i])] = findRoot(parent, order[j]);
            }
        }
    // The largest component, then its diameter by two shortest-path sweeps.
    std::map<std::size_t, std::size_t> sizes;
    for (std::size_t i = 0; i < s.size(); ++i)
        ++sizes[findRoot(parent, i)];
    const std::size_t root =
        std::max_element(sizes.begin(), sizes.end(),
                         [](const auto& a, const auto& b) { return a.second < b.second; })
            ->first;
    std::size_t start = 0;
    while (findRoot(parent, start) != root)
        ++start;
    std::vector<double> dist;
    std::vector<std::size_t> previous;
    auto farthest = [&]()
    {
        std::size_t best = start;
        for (std::size_t i = 0; i < s.size(); ++i)
            if (std::isfinite(dist[i]) && dist[i] > dist[best]) best = i;
        return best;
    };
    std::vector<osg::Vec2d> centres;
    for (const Street& street : s)
        centres.push_back(street.centre);
    shortestPaths(adjacent, centres, start, dist, previous);
    const std::size_t u = farthest();
    shortestPaths(adjacent, centres, u, dist, previous);
    std::size_t v = u;
    for (std::size_t i = 0; i < s.size(); ++i)
        if (std::isfinite(dist[i]) && dist[i] > dist[v]) v = i;
    std::vector<osg::Vec2d> path;
    for (std::size_t n = v; n != s.size(); n = previous[n])
        path.push_back(s[n].centre);
    std::reverse(path.begin(), path.end());
    if (features) *features = unsigned(path.size());
    if (path.size() == 1) return path;
    return simplified(path, tolerance);
}

void ScenarioFitting::fit(const UsageScenario& scenario, const FeatureIndex& index)
{
    _notes.clear();
    _viewMetrics.clear();
    _lastScale = -1.0;
    osg::BoundingBoxd box;
    for (const FeatureIndex::Entry& e : index.entries())
        if (e.feature->getBound().valid())
            box.expandBy(osg::BoundingBoxd(osg::Vec3d(e.feature->getBound()._min),
                                           osg::Vec3d(e.feature->getBound()._max)));
    _centre = box.valid() ? box.center() : osg::Vec3d();
    _size = box.valid() ? 0.5 * std::hypot(box.xMax() - box.xMin(), box.yMax() - box.yMin()) : 0.0;

    bool needed = scenario.getFocusFeature() == 0 && scenario.getFocusTallestLandmark();
    for (const auto& c : scenario.getConfigurations())
        for (const auto& m : c->getMetrics())
            needed = needed || (m.valid() && m->getScale() != SaliencyMetric::ABSOLUTE);
    for (const auto& r : scenario.getRegions())
        needed = needed || (r.valid() && !r->isResolved());
    if (!needed)
    {
        _scenario = const_cast<UsageScenario*>(&scenario); // bound as it is, never modified
        return;
    }
    _scenario = osg::clone(&scenario, osg::CopyOp::DEEP_COPY_ALL);
    std::ostringstream head;
    head << "scene: centre (" << metres(_centre.x()) << ", " << metres(_centre.y())
         << "), size S = " << metres(_size) << " (half the horizontal diagonal of the features' box)";
    _notes.push_back(head.str());

    for (const auto& c : _scenario->getConfigurations())
        for (const auto& m : c->getMetrics())
        {
            if (!m.valid() || m->getScale() == SaliencyMetric::ABSOLUTE) continue;
            const double n = m->getNear(), f = m->getFar();
            if (m->getScale() == SaliencyMetric::VIEW) _viewMetrics.push_back({m.get(), n, f});
            m->setNear(n * _size);
            m->setFar(f * _size);
            m->setScale(SaliencyMetric::ABSOLUTE);
        }
    if (!_viewMetrics.empty())
        _notes.push_back("view-scaled metrics: near and far times the eye's distance to the scene centre, "
                         "every frame");

    for (auto& r : _scenario->getRegions())
    {
        if (!r.valid() || r->isResolved()) continue;
        const std::string label = "region '" + r->getName() + "'";
        const double scale = r->getSceneScale() ? _size : 1.0;
        osg::Vec2d anchor;
        std::string where;
        switch (r->getPlacement())
        {
        case RegionOfInterest::SCENE_CENTRE:
            anchor.set(_centre.x(), _centre.y());
            where = "at the scene centre";
            break;
        case RegionOfInterest::FEATURE:
        {
            const Feature* f = nullptr;
            if (r->getPlacementFeature() != 0)
            {
                const FeatureIndex::Entry* e = index.find(r->getPlacementFeature());
                if (!e)
                    throw std::invalid_argument(label + " is placed at feature " +
                                                std::to_string(r->getPlacementFeature()) +
                                                ", which this model does not have");
                f = e->feature.get();
            }
            else
                f = tallest(index);
            if (f && f->getBound().valid())
            {
                anchor.set(f->getBound().center().x(), f->getBound().center().y());
                where = "at feature " + std::to_string(f->getId()) +
                        (r->getPlacementFeature() ? "" : " (the tallest)");
            }
            else
            {
                anchor.set(_centre.x(), _centre.y());
                where = "at the scene centre (the model has no building to place it at)";
            }
            break;
        }
        case RegionOfInterest::LONGEST_STREET:
        {
            unsigned n = 0;
            RegionOfInterest::Vertices chain = longestStreetChain(index, 0.01 * _size, &n);
            if (chain.size() < 2)
            {
                // No street chain: along the scene's long axis through its centre.
                const double hx = box.valid() ? 0.4 * (box.xMax() - box.xMin()) : 0.0;
                const double hy = box.valid() ? 0.4 * (box.yMax() - box.yMin()) : 0.0;
                chain = hx >= hy ? RegionOfInterest::Vertices{{_centre.x() - hx, _centre.y()},
                                                              {_centre.x() + hx, _centre.y()}}
                                 : RegionOfInterest::Vertices{{_centre.x(), _centre.y() - hy},
                                                              {_centre.x(), _centre.y() + hy}};
                where = "along the scene's long axis (no chain of touching street features)";
                OSG_NOTICE << "osgLoA: " << label
                           << ": the model has no chain of touching street features; the "
                           << "route runs along the scene's long axis" << std::endl;
            }
            else
            {
                double length = 0.0;
                for (std::size_t i = 1; i < chain.size(); ++i)
                    length += (chain[i] - chain[i - 1]).length();
                where = "along the longest street chain (" + std::to_string(n) + " features, " +
                        metres(length) + " long, " + std::to_string(chain.size()) + " vertices)";
            }
            r->setShape(RegionOfInterest::POLYLINE);
            r->setVertices(chain);
            r->setRadius(r->getRadius() * scale);
            r->setPlacement(RegionOfInterest::ABSOLUTE);
            r->setSceneScale(false);
            _notes.push_back(label + " " + where + ", radius " + metres(r->getRadius()));
            continue;
        }
        default:
            where = "in scene coordinates";
            break;
        }
        for (osg::Vec2d& v : r->getVertices())
            v = anchor + v * scale;
        r->setRadius(r->getRadius() * scale);
        r->setPlacement(RegionOfInterest::ABSOLUTE);
        r->setSceneScale(false);
        _notes.push_back(label + " " + where + ", radius " + metres(r->getRadius()));
    }

    if (_scenario->getFocusFeature() == 0 && _scenario->getFocusTallestLandmark())
    {
        if (const Feature* f = tallest(index))
        {
            _scenario->setFocusFeature(f->getId());
            _scenario->setFocusTallestLandmark(false);
            _notes.push_back("focus: feature " + std::to_string(f->getId()) + ", the tallest " +
                             (f->getLandmark() ? "landmark" : "building") + " (" +
                             metres(f->getBound().zMax() - f->getBound().zMin()) + " high)");
        }
        else
            _notes.push_back("focus: none (the model has no building or landmark)");
    }
    if (!_viewMetrics.empty()) applyEye(_centre + osg::Vec3d(0.0, 0.0, _size)); // until the first frame
}

bool ScenarioFitting::applyEye(const osg::Vec3d& eye)
{
    if (_viewMetrics.empty()) return false;
    const double d = (eye - _centre).length();
    if (std::fabs(d - _lastScale) <= 1e-9 * std::max(d, 1.0)) return false;
    _lastScale = d;
    for (const ViewMetric& v : _viewMetrics)
    {
        v.metric->setNear(v.nearFactor * d);
        v.metric->setFar(v.farFactor * d);
    }
    return true;
}

} // namespace osgLoA
