/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/filtering/TexturePageTable>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

namespace osgLoA
{

int TexturePageTable::registerTexture(const osg::Texture2D& texture, unsigned unit)
{
    auto it = _byTexture.find({&texture, unit});
    if (it != _byTexture.end() && _entries[std::size_t(it->second)].texture.get() == &texture)
        return it->second;
    const osg::Image* image = texture.getImage();
    const std::string name = image && !image->getFileName().empty() ? "'" + image->getFileName() + "'"
                                                                    : "'" + texture.getName() + "'";
    if (!image || image->s() <= 0 || image->t() <= 0 || !image->data())
        throw std::invalid_argument("TexturePageTable: texture " + name + " on unit " + std::to_string(unit) +
                                    " has no image to register");
    const int tid = add(FilterImage::fromImage(*image), ImageBorder::of(texture), unit, &texture);
    _byTexture[{&texture, unit}] = tid;
    return tid;
}

int TexturePageTable::registerImage(const FilterImage& level0, const ImageBorder& border, unsigned unit)
{
    if (level0.empty()) throw std::invalid_argument("TexturePageTable: empty image");
    return add(level0, border, unit, nullptr);
}

int TexturePageTable::add(const FilterImage& level0, const ImageBorder& border, unsigned unit,
                          const osg::Texture2D* texture)
{
    Entry e;
    e.texture = texture;
    e.unit = unit;
    e.width = level0.width();
    e.height = level0.height();
    e.border = border;
    e.firstRegion = int(_regions.size());
    std::vector<FilterImage> levels = level0.mipPyramid();
    e.levels = int(levels.size());
    for (int l = 0; l < e.levels; ++l)
    {
        GpuFilterEngine::Region r;
        r.width = levels[std::size_t(l)].width();
        r.height = levels[std::size_t(l)].height();
        r.border = border;
        _regions.push_back(r);
        _levelOfRegion.push_back(l);
        _textureOfRegion.push_back(int(_entries.size()));
        _tileBase.push_back(_tileCount);
        _tileCount += std::size_t(r.tilesX()) * std::size_t(r.tilesY());
    }
    _entries.push_back(e);
    _levels.push_back(std::move(levels));
    _packed = false;
    return int(_entries.size()) - 1;
}

int TexturePageTable::find(const osg::Texture2D* texture, unsigned unit) const
{
    auto it = _byTexture.find({texture, unit});
    if (it == _byTexture.end() || _entries[std::size_t(it->second)].texture.get() != texture) return -1;
    return it->second;
}

const FilterImage& TexturePageTable::levelImage(int tid, int level) const
{
    return _levels.at(std::size_t(tid)).at(std::size_t(level));
}

namespace
{
/** Shelf packing at a fixed width: regions in the given order (tallest first) left to right,
 *  a new shelf when one does not fit. Returns the height; positions into xs/ys. */
int shelfPack(const std::vector<GpuFilterEngine::Region>& regions, const std::vector<std::size_t>& order,
              int width, std::vector<int>& xs, std::vector<int>& ys)
{
    int x = 0, y = 0, shelf = 0;
    for (std::size_t i : order)
    {
        const GpuFilterEngine::Region& r = regions[i];
        if (x + r.width > width)
        {
            y += shelf;
            x = 0;
            shelf = 0;
        }
        xs[i] = x;
        ys[i] = y;
        x += r.width;
        shelf = std::max(shelf, r.height);
    }
    return y + shelf;
}
} // namespace

void TexturePageTable::pack(int maxSize)
{
    if (_regions.empty())
    {
        _atlasWidth = _atlasHeight = 1; // a valid (unused) 1x1 atlas
        _packed = true;
        return;
    }
    std::vector<std::size_t> order(_regions.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return _regions[a].height > _regions[b].height; });
    double area = 0;
    int widest = 0;
    for (const auto& r : _regions)
    {
        area += double(r.width) * r.height;
        widest = std::max(widest, r.width);
    }
    // Candidate widths: the widest region up to twice it, and around the square root of the area.
    std::vector<int> candidates;
    for (int k = 4; k <= 8; ++k)
        candidates.push_back(widest * k / 4);
    for (double f : {1.0, 1.25, 1.5})
        candidates.push_back(std::max(widest, int(std::ceil(std::sqrt(area) * f))));
    std::vector<int> xs(_regions.size()), ys(_regions.size()), bx, by;
    int bestW = 0, bestH = 0;
    double bestArea = 0;
    for (int w : candidates)
    {
        if (w > maxSize) continue;
        const int h = shelfPack(_regions, order, w, xs, ys);
        if (h > maxSize) continue;
        const double a = double(w) * h;
        if (bestW == 0 || a < bestArea || (a == bestArea && std::max(w, h) < std::max(bestW, bestH)))
        {
            bestW = w;
            bestH = h;
            bestArea = a;
            bx = xs;
            by = ys;
        }
    }
    if (bestW == 0)
        throw std::invalid_argument("TexturePageTable: the " + std::to_string(_entries.size()) +
                                    " textures' mip levels (" + std::to_string(std::llround(area)) +
                                    " texels) do not fit an atlas of at most " + std::to_string(maxSize) +
                                    "x" + std::to_string(maxSize));
    for (std::size_t i = 0; i < _regions.size(); ++i)
    {
        _regions[i].x = bx[i];
        _regions[i].y = by[i];
    }
    _atlasWidth = bestW;
    _atlasHeight = bestH;
    _packed = true;
}

double TexturePageTable::packingEfficiency() const
{
    double used = 0;
    for (const auto& r : _regions)
        used += double(r.width) * r.height;
    return _atlasWidth > 0 && _atlasHeight > 0 ? used / (double(_atlasWidth) * _atlasHeight) : 0.0;
}

FilterImage TexturePageTable::atlasImage() const
{
    if (!_packed) throw std::logic_error("TexturePageTable::atlasImage: pack() first");
    FilterImage atlas(_atlasWidth, _atlasHeight);
    for (std::size_t r = 0; r < _regions.size(); ++r)
    {
        const GpuFilterEngine::Region& reg = _regions[r];
        const FilterImage& img = _levels[std::size_t(_textureOfRegion[r])][std::size_t(_levelOfRegion[r])];
        for (int y = 0; y < reg.height; ++y)
            std::copy(img.texel(0, y), img.texel(0, y) + std::size_t(reg.width) * 4,
                      atlas.texel(reg.x, reg.y + y));
    }
    return atlas;
}

std::vector<int> TexturePageTable::pageTableData() const
{
    std::vector<int> d;
    d.reserve(_entries.size() * 8);
    for (const Entry& e : _entries)
        d.insert(d.end(), {e.width, e.height, e.levels, int(e.unit), int(e.border.s), int(e.border.t),
                           e.firstRegion, 0});
    return d;
}

std::vector<int> TexturePageTable::regionTableData() const
{
    std::vector<int> d;
    d.reserve(_regions.size() * 8);
    for (std::size_t i = 0; i < _regions.size(); ++i)
    {
        const GpuFilterEngine::Region& r = _regions[i];
        d.insert(d.end(),
                 {r.x, r.y, r.width, r.height, int(_tileBase[i]), r.tilesX(), r.tilesY(), _levelOfRegion[i]});
    }
    return d;
}

void TexturePageTable::clear()
{
    _entries.clear();
    _levels.clear();
    _regions.clear();
    _levelOfRegion.clear();
    _textureOfRegion.clear();
    _tileBase.clear();
    _tileCount = 0;
    _byTexture.clear();
    _atlasWidth = _atlasHeight = 0;
    _packed = false;
}

} // namespace osgLoA
