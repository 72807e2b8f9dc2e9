/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include "FeatureGroundRaster.h"
#include "TriangleCollector.h"

#include <osgLoA/semantics/Feature>
#include <osgLoA/semantics/FeatureIndex>

#include <osg/Image>

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>
#include <string>

namespace osgLoA
{

FeatureTriangles collectFeatureTriangles(osg::Node& model, FeatureType type)
{
    FeatureTriangles out;
    FeatureIndex index(model);
    std::set<const Feature*> features;
    for (const FeatureIndex::Entry& e : index.entries())
    {
        osg::ref_ptr<osg::Node> node;
        if (e.feature->getType() != type || !e.node.lock(node)) continue;
        // A nested feature is collected with its enclosing one when that is of its type too.
        if (e.parent >= 0 && index.entries()[std::size_t(e.parent)].feature->getType() == type) continue;
        features.insert(e.feature.get());
        out.parts.push_back({node, out.corners.size()});
        osg::NodePath path = index.pathOf(e);
        if (!path.empty()) path.pop_back();
        TriangleCollector collect(osg::computeLocalToWorld(path), osg::NodeVisitor::TRAVERSE_ALL_CHILDREN);
        collect.setNodeMaskOverride(~0u);
        node->accept(collect);
        const std::vector<osg::Vec3d>& c = collect.corners();
        for (std::size_t t = 0; t + 2 < c.size(); t += 3)
        {
            // Walls and other faces without a ground footprint cover no texel centre.
            const double area2 = (c[t + 1].x() - c[t].x()) * (c[t + 2].y() - c[t].y()) -
                                 (c[t + 2].x() - c[t].x()) * (c[t + 1].y() - c[t].y());
            if (!std::isfinite(area2) || std::fabs(area2) < 1e-12) continue;
            out.corners.insert(out.corners.end(), c.begin() + std::ptrdiff_t(t),
                               c.begin() + std::ptrdiff_t(t + 3));
        }
    }
    out.features = unsigned(features.size());
    return out;
}

void checkGridParameters(const char* who, int resolution, double minTexelSize)
{
    if (resolution < 3 || resolution > DistanceField::kMaxResolution)
        throw std::invalid_argument(std::string(who) + ": resolution " + std::to_string(resolution) +
                                    " is not in 3.." + std::to_string(DistanceField::kMaxResolution));
    if (!std::isfinite(minTexelSize) || minTexelSize < 0.0)
        throw std::invalid_argument(std::string(who) + ": minimum texel size " +
                                    std::to_string(minTexelSize) + " is not finite and >= 0");
}

DistanceField::Grid footprintGrid(const std::vector<osg::Vec3d>& corners, int resolution, double minTexelSize,
                                  double* extentOut)
{
    osg::BoundingBoxd box;
    for (const osg::Vec3d& c : corners)
        box.expandBy(osg::Vec3d(c.x(), c.y(), 0.0));
    const double extent = box.valid() ? std::max(box.xMax() - box.xMin(), box.yMax() - box.yMin()) : 0.0;
    if (extentOut) *extentOut = extent;
    if (!(extent > 0.0) || !std::isfinite(extent)) return DistanceField::Grid();
    const double texel = std::max(extent / double(resolution - 2), minTexelSize);
    const osg::BoundingBoxd area(box.xMin() - texel, box.yMin() - texel, 0.0, box.xMax() + texel,
                                 box.yMax() + texel, 0.0);
    return DistanceField::Grid::cover(area, texel, resolution);
}

void rasterizeHeights(const DistanceField::Grid& g, const std::vector<osg::Vec3d>& tris, bool highest,
                      std::vector<double>& cells)
{
    for (std::size_t t = 0; t + 2 < tris.size(); t += 3)
    {
        const osg::Vec2d a = g.worldToTexel(osg::Vec2d(tris[t].x(), tris[t].y())),
                         b = g.worldToTexel(osg::Vec2d(tris[t + 1].x(), tris[t + 1].y())),
                         c = g.worldToTexel(osg::Vec2d(tris[t + 2].x(), tris[t + 2].y()));
        const double orient = (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
        if (orient == 0.0) continue;
        const int i0 = std::max(0, int(std::floor(std::min({a.x(), b.x(), c.x()}) - 0.5)));
        const int i1 = std::min(g.width - 1, int(std::ceil(std::max({a.x(), b.x(), c.x()}) - 0.5)));
        const int j0 = std::max(0, int(std::floor(std::min({a.y(), b.y(), c.y()}) - 0.5)));
        const int j1 = std::min(g.height - 1, int(std::ceil(std::max({a.y(), b.y(), c.y()}) - 0.5)));
        auto edge = [&](const osg::Vec2d& p, const osg::Vec2d& q, double x, double y)
        { return ((q.x() - p.x()) * (y - p.y()) - (x - p.x()) * (q.y() - p.y())) / orient; };
        for (int j = j0; j <= j1; ++j)
            for (int i = i0; i <= i1; ++i)
            {
                const double x = i + 0.5, y = j + 0.5;
                // Barycentric weights of a, b, c (each >= 0 inside).
                const double wa = edge(b, c, x, y), wb = edge(c, a, x, y), wc = edge(a, b, x, y);
                if (wa < 0 || wb < 0 || wc < 0) continue;
                const double z = wa * tris[t].z() + wb * tris[t + 1].z() + wc * tris[t + 2].z();
                double& cell = cells[std::size_t(j) * std::size_t(g.width) + std::size_t(i)];
                cell = highest ? std::max(cell, z) : std::min(cell, z);
            }
    }
}

float sampleBilinear(const DistanceField::Grid& grid, const std::vector<float>& values, double x, double y)
{
    const osg::Vec2d t = grid.worldToTexel(osg::Vec2d(x, y)) - osg::Vec2d(0.5, 0.5);
    const double fx = std::clamp(t.x(), 0.0, double(grid.width - 1));
    const double fy = std::clamp(t.y(), 0.0, double(grid.height - 1));
    const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
    const int x1 = std::min(x0 + 1, grid.width - 1), y1 = std::min(y0 + 1, grid.height - 1);
    const double ax = fx - x0, ay = fy - y0;
    auto at = [&](int i, int j)
    { return double(values[std::size_t(j) * std::size_t(grid.width) + std::size_t(i)]); };
    return float((1 - ay) * ((1 - ax) * at(x0, y0) + ax * at(x1, y0)) +
                 ay * ((1 - ax) * at(x0, y1) + ax * at(x1, y1)));
}

osg::ref_ptr<osg::Texture2D> createGridTexture(const DistanceField::Grid& grid,
                                               const std::vector<float>& values, const std::string& name,
                                               bool linear)
{
    osg::ref_ptr<osg::Image> image = new osg::Image;
    image->allocateImage(grid.width, grid.height, 1, GL_RED, GL_FLOAT);
    image->setInternalTextureFormat(GL_R32F);
    std::copy(values.begin(), values.end(), reinterpret_cast<float*>(image->data()));
    osg::ref_ptr<osg::Texture2D> texture = new osg::Texture2D(image.get());
    texture->setName(name);
    texture->setInternalFormat(GL_R32F);
    texture->setSourceFormat(GL_RED);
    texture->setSourceType(GL_FLOAT);
    const osg::Texture::FilterMode mode = linear ? osg::Texture::LINEAR : osg::Texture::NEAREST;
    texture->setFilter(osg::Texture::MIN_FILTER, mode);
    texture->setFilter(osg::Texture::MAG_FILTER, mode);
    texture->setWrap(osg::Texture::WRAP_S, osg::Texture::CLAMP_TO_EDGE);
    texture->setWrap(osg::Texture::WRAP_T, osg::Texture::CLAMP_TO_EDGE);
    texture->setResizeNonPowerOfTwoHint(false);
    texture->setUseHardwareMipMapGeneration(false);
    return texture;
}

} // namespace osgLoA
