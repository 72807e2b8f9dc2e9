// RoutedRegion: the tiles of a viewport where routed (order-independent) draws can put fragments.
#include <osgLoA/compositing/RoutedRegion>

#include <osg/Drawable>
#include <osgUtil/RenderBin>
#include <osgUtil/RenderLeaf>
#include <osgUtil/StateGraph>

#include <algorithm>
#include <cmath>

namespace osgLoA
{

RoutedRegion::RoutedRegion(int x, int y, int width, int height, int tileSize)
    : _x(x), _y(y), _width(std::max(0, width)), _height(std::max(0, height)), _tile(std::max(1, tileSize))
{
    _cols = (_width + _tile - 1) / _tile;
    _rows = (_height + _tile - 1) / _tile;
    _mask.assign(std::size_t(_cols) * std::size_t(_rows), 0);
}

void RoutedRegion::addWindowBox(double x0, double y0, double x1, double y1)
{
    if (!(x1 > x0) || !(y1 > y0) || _cols == 0 || _rows == 0) return;
    // Local pixels, one pixel of margin; the last pixel touched is ceil(x1) - 1 + 1.
    const double lx0 = x0 - _x - 1.0, ly0 = y0 - _y - 1.0, lx1 = x1 - _x + 1.0, ly1 = y1 - _y + 1.0;
    if (lx1 <= 0.0 || ly1 <= 0.0 || lx0 >= _width || ly0 >= _height) return;
    const int c0 = std::max(0, int(std::floor(lx0 / _tile)));
    const int r0 = std::max(0, int(std::floor(ly0 / _tile)));
    const int c1 = std::min(_cols - 1, int(std::floor((std::min(lx1, double(_width)) - 1e-9) / _tile)));
    const int r1 = std::min(_rows - 1, int(std::floor((std::min(ly1, double(_height)) - 1e-9) / _tile)));
    _rectanglesValid = false;
    for (int r = r0; r <= r1; ++r)
        std::fill(_mask.begin() + r * _cols + c0, _mask.begin() + r * _cols + c1 + 1, std::uint8_t(255));
}

void RoutedRegion::addBox(const osg::BoundingBox& box, const osg::Matrix& modelView,
                          const osg::Matrix& projection)
{
    if (!box.valid()) return;
    const osg::Matrix mvp = modelView * projection;
    double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
    for (unsigned i = 0; i < 8; ++i)
    {
        const osg::Vec3d c(box.corner(i));
        const double cx = c.x() * mvp(0, 0) + c.y() * mvp(1, 0) + c.z() * mvp(2, 0) + mvp(3, 0);
        const double cy = c.x() * mvp(0, 1) + c.y() * mvp(1, 1) + c.z() * mvp(2, 1) + mvp(3, 1);
        const double cw = c.x() * mvp(0, 3) + c.y() * mvp(1, 3) + c.z() * mvp(2, 3) + mvp(3, 3);
        if (!(cw > 1e-9))
        {
            // The box reaches the eye plane: its projection is unbounded.
            addAll();
            return;
        }
        const double wx = _x + (cx / cw * 0.5 + 0.5) * _width;
        const double wy = _y + (cy / cw * 0.5 + 0.5) * _height;
        x0 = std::min(x0, wx);
        y0 = std::min(y0, wy);
        x1 = std::max(x1, wx);
        y1 = std::max(y1, wy);
    }
    addWindowBox(x0, y0, x1, y1);
}

void RoutedRegion::addAll()
{
    _rectanglesValid = false;
    std::fill(_mask.begin(), _mask.end(), std::uint8_t(255));
}

void RoutedRegion::addRenderBin(const osgUtil::RenderBin& bin)
{
    auto addLeaf = [this](const osgUtil::RenderLeaf* leaf)
    {
        if (!leaf || !leaf->getDrawable()) return;
        if (!leaf->_modelview.valid() || !leaf->_projection.valid())
        {
            addAll();
            return;
        }
        addBox(leaf->getDrawable()->getBoundingBox(), *leaf->_modelview, *leaf->_projection);
    };
    for (const osgUtil::RenderLeaf* leaf : bin.getRenderLeafList())
        addLeaf(leaf);
    for (const osgUtil::StateGraph* sg : bin.getStateGraphList())
        for (const auto& leaf : sg->_leaves)
            addLeaf(leaf.get());
    for (const auto& sub : bin.getRenderBinList())
        addRenderBin(*sub.second);
}

int RoutedRegion::countTiles() const
{
    return int(std::count(_mask.begin(), _mask.end(), std::uint8_t(255)));
}

std::uint64_t RoutedRegion::countPixels() const
{
    std::uint64_t n = 0;
    for (const Rect& r : rectangles())
        n += std::uint64_t(r.width) * std::uint64_t(r.height);
    return n;
}

const std::vector<RoutedRegion::Rect>& RoutedRegion::rectangles() const
{
    if (_rectanglesValid) return _rectangles;
    std::vector<Rect>& out = _rectangles;
    out.clear();
    std::vector<std::size_t> open; // rectangles ending at the row below, by index into out
    for (int r = 0; r < _rows; ++r)
    {
        std::vector<std::size_t> next;
        int c = 0;
        while (c < _cols)
        {
            if (!isSet(c, r))
            {
                ++c;
                continue;
            }
            int e = c;
            while (e < _cols && isSet(e, r))
                ++e;
            Rect run;
            run.x = _x + c * _tile;
            run.y = _y + r * _tile;
            run.width = std::min(_width, e * _tile) - c * _tile;
            run.height = std::min(_height, (r + 1) * _tile) - r * _tile;
            bool merged = false;
            for (std::size_t k : open)
                if (out[k].x == run.x && out[k].width == run.width && out[k].y + out[k].height == run.y)
                {
                    out[k].height += run.height;
                    next.push_back(k);
                    merged = true;
                    break;
                }
            if (!merged)
            {
                out.push_back(run);
                next.push_back(out.size() - 1);
            }
            c = e;
        }
        open.swap(next);
    }
    _rectanglesValid = true;
    return out;
}

} // namespace osgLoA
