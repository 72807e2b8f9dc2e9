#include <osgLoA/util/PolygonCrossings>

#include <algorithm>
#include <cmath>

namespace osgLoA
{
namespace
{
struct Edge
{
    osg::Vec2d a, b;
    std::size_t ring, index; ///< index within its ring (neighbours share a vertex)
    std::size_t ringSize;
};

double cross(const osg::Vec2d& o, const osg::Vec2d& a, const osg::Vec2d& b)
{
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

/** The proper crossing point of two segments (each strictly crosses the other's line). */
bool properCrossing(const Edge& e, const Edge& f, osg::Vec2d& point)
{
    const double d1 = cross(e.a, e.b, f.a), d2 = cross(e.a, e.b, f.b);
    const double d3 = cross(f.a, f.b, e.a), d4 = cross(f.a, f.b, e.b);
    if (!(((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))))
        return false;
    const double t = d3 / (d3 - d4);
    point = e.a + (e.b - e.a) * t;
    return true;
}

bool adjacent(const Edge& e, const Edge& f)
{
    if (e.ring != f.ring) return false;
    const std::size_t n = e.ringSize;
    return (e.index + 1) % n == f.index || (f.index + 1) % n == e.index;
}
} // namespace

PolygonCrossings PolygonCrossings::count(const std::vector<std::vector<osg::Vec2d>>& rings,
                                         std::size_t maxCrossings, std::size_t maxTests)
{
    PolygonCrossings result;
    std::vector<Edge> edges;
    double minX = HUGE_VAL, minY = HUGE_VAL, maxX = -HUGE_VAL, maxY = -HUGE_VAL;
    for (std::size_t r = 0; r < rings.size(); ++r)
    {
        const std::size_t n = rings[r].size();
        if (n < 3) continue;
        for (std::size_t i = 0; i < n; ++i)
        {
            const osg::Vec2d& p = rings[r][i];
            minX = std::min(minX, p.x()), maxX = std::max(maxX, p.x());
            minY = std::min(minY, p.y()), maxY = std::max(maxY, p.y());
            edges.push_back({p, rings[r][(i + 1) % n], r, i, n});
        }
    }
    if (edges.size() < 4 || !(maxX > minX) || !(maxY > minY)) return result;

    // About four cells per edge (rings fill a thin band of the box, not all of it).
    const std::size_t side =
        std::max<std::size_t>(1, static_cast<std::size_t>(std::sqrt(4.0 * double(edges.size()))));
    const double cw = (maxX - minX) / double(side), ch = (maxY - minY) / double(side);
    const auto cellX = [&](double x)
    { return std::min(side - 1, static_cast<std::size_t>(std::max(0.0, (x - minX) / cw))); };
    const auto cellY = [&](double y)
    { return std::min(side - 1, static_cast<std::size_t>(std::max(0.0, (y - minY) / ch))); };
    std::vector<std::vector<std::size_t>> cells(side * side);
    for (std::size_t k = 0; k < edges.size(); ++k)
    {
        // Amanatides & Woo: the cells the segment passes, from a's to b's.
        const Edge& e = edges[k];
        std::size_t x = cellX(e.a.x()), y = cellY(e.a.y());
        const std::size_t xEnd = cellX(e.b.x()), yEnd = cellY(e.b.y());
        const osg::Vec2d d = e.b - e.a;
        const long stepX = d.x() > 0 ? 1 : -1, stepY = d.y() > 0 ? 1 : -1;
        const double nextX = minX + cw * double(x + (stepX > 0 ? 1 : 0));
        const double nextY = minY + ch * double(y + (stepY > 0 ? 1 : 0));
        double tMaxX = d.x() != 0 ? (nextX - e.a.x()) / d.x() : HUGE_VAL;
        double tMaxY = d.y() != 0 ? (nextY - e.a.y()) / d.y() : HUGE_VAL;
        const double tDeltaX = d.x() != 0 ? cw / std::abs(d.x()) : HUGE_VAL;
        const double tDeltaY = d.y() != 0 ? ch / std::abs(d.y()) : HUGE_VAL;
        for (std::size_t guard = 0; guard < 4 * side + 4; ++guard)
        {
            cells[y * side + x].push_back(k);
            if (x == xEnd && y == yEnd) break;
            if (tMaxX < tMaxY)
            {
                if (x == xEnd) break;
                x = std::size_t(long(x) + stepX), tMaxX += tDeltaX;
            }
            else
            {
                if (y == yEnd) break;
                y = std::size_t(long(y) + stepY), tMaxY += tDeltaY;
            }
        }
    }

    for (std::size_t c = 0; c < cells.size(); ++c)
    {
        const std::vector<std::size_t>& in = cells[c];
        const std::size_t cx = c % side, cy = c / side;
        for (std::size_t i = 0; i < in.size(); ++i)
            for (std::size_t j = i + 1; j < in.size(); ++j)
            {
                if (++result.tests > maxTests)
                {
                    result.tooComplex = true;
                    return result;
                }
                const Edge &e = edges[in[i]], &f = edges[in[j]];
                osg::Vec2d p;
                if (adjacent(e, f) || !properCrossing(e, f, p)) continue;
                if (cellX(p.x()) != cx || cellY(p.y()) != cy) continue; // counted in its own cell
                if (++result.crossings >= maxCrossings)
                {
                    result.tooMany = true;
                    return result;
                }
            }
    }
    return result;
}

} // namespace osgLoA
