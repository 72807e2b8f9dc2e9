#include <osgLoA/city/CityTextures>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <stdexcept>

namespace osgLoA
{
namespace
{
// Integer hash noise: identical on every platform.
std::uint32_t hash3(std::uint32_t x, std::uint32_t y, std::uint32_t s)
{
    std::uint32_t h = x * 0x8da6b343u ^ y * 0xd8163841u ^ s * 0xcb1ab31fu;
    h ^= h >> 15;
    h *= 0x2c1b3c6du;
    h ^= h >> 12;
    h *= 0x297a2d39u;
    h ^= h >> 15;
    return h;
}
int noise(int x, int y, int s, int amplitude)
{
    return static_cast<int>(hash3(static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y),
                                  static_cast<std::uint32_t>(s)) %
                            static_cast<std::uint32_t>(2 * amplitude + 1)) -
           amplitude;
}

struct Rgb
{
    int r, g, b;
};

class Canvas
{
public:
    Canvas(const std::string& name, int w, int h) : _img(new osg::Image)
    {
        _img->allocateImage(w, h, 1, GL_RGB, GL_UNSIGNED_BYTE);
        _img->setFileName("loa_" + name + ".png");
        _img->setName(name);
    }
    int w() const { return _img->s(); }
    int h() const { return _img->t(); }
    void set(int x, int y, Rgb c)
    {
        unsigned char* p = _img->data(x, y);
        p[0] = static_cast<unsigned char>(std::clamp(c.r, 0, 255));
        p[1] = static_cast<unsigned char>(std::clamp(c.g, 0, 255));
        p[2] = static_cast<unsigned char>(std::clamp(c.b, 0, 255));
    }
    void fillNoise(Rgb base, int amp, int seed)
    {
        for (int y = 0; y < h(); ++y)
            for (int x = 0; x < w(); ++x)
            {
                const int n = noise(x, y, seed, amp);
                set(x, y, {base.r + n, base.g + n, base.b + n});
            }
    }
    void rect(int x0, int y0, int x1, int y1, Rgb c, int amp = 0, int seed = 0)
    {
        for (int y = std::max(0, y0); y < std::min(h(), y1); ++y)
            for (int x = std::max(0, x0); x < std::min(w(), x1); ++x)
            {
                const int n = amp ? noise(x, y, seed, amp) : 0;
                set(x, y, {c.r + n, c.g + n, c.b + n});
            }
    }
    osg::ref_ptr<osg::Image> image() { return _img; }

private:
    osg::ref_ptr<osg::Image> _img;
};

// Windows of one bay x one floor cell: frame, glass with a vertical gradient, sill.
void drawWindow(Canvas& c, int x0, int y0, int cw, int ch, double wFrac, double hFrac, Rgb frame, Rgb glass,
                int seed)
{
    const int ww = std::max(2, static_cast<int>(cw * wFrac)), wh = std::max(2, static_cast<int>(ch * hFrac));
    const int wx = x0 + (cw - ww) / 2, wy = y0 + (ch - wh) / 2 + ch / 12;
    c.rect(wx - 1, wy - 1, wx + ww + 1, wy + wh + 1, frame);
    const bool lit = noise(x0, y0, seed, 50) > 38; // a few lit windows
    for (int y = wy; y < wy + wh; ++y)
        for (int x = wx; x < wx + ww; ++x)
        {
            const int grad = (y - wy) * 40 / std::max(1, wh);
            Rgb g = lit ? Rgb{230, 210, 140} : Rgb{glass.r + grad, glass.g + grad, glass.b + grad};
            c.set(x, y, g);
        }
    // Mullion.
    if (ww > 8) c.rect(wx + ww / 2, wy, wx + ww / 2 + 1, wy + wh, frame);
    c.rect(wx - 2, wy - 3, wx + ww + 2, wy - 1, {frame.r - 30, frame.g - 30, frame.b - 30});
}
/** Generated images by key, made once per process and shared (STATIC: nobody changes them).
 *  Deep copies cost an OSM import 17 % of its time under the fuzzer (issue 22 item 5). */
osg::ref_ptr<osg::Image> cached(const std::string& key, const std::function<osg::ref_ptr<osg::Image>()>& make)
{
    static std::mutex mutex;
    static std::map<std::string, osg::ref_ptr<osg::Image>> images;
    osg::ref_ptr<osg::Image> original;
    {
        std::lock_guard<std::mutex> lock(mutex);
        auto it = images.find(key);
        if (it != images.end()) original = it->second;
    }
    if (!original)
    {
        original = make(); // outside the lock: generation is the slow part
        original->setDataVariance(osg::Object::STATIC);
        std::lock_guard<std::mutex> lock(mutex);
        original = images.emplace(key, original).first->second; // a racing thread's image wins
    }
    return original;
}
} // namespace

osg::ref_ptr<osg::Image> CityTextures::facade(const FacadeStyle& s)
{
    return cached("facade|" + s.name + "|" + std::to_string(s.width) + "x" + std::to_string(s.height) + "|" +
                      std::to_string(s.bays) + "x" + std::to_string(s.floors),
                  [&] { return generateFacade(s); });
}

osg::ref_ptr<osg::Image> CityTextures::surface(const std::string& kind)
{
    return cached("surface|" + kind, [&] { return generateSurface(kind); });
}

const std::vector<FacadeStyle>& CityTextures::facadeStyles()
{
    // Sizes mix powers of two and non-powers of two (192x160, 96x96, 320x200) on purpose.
    static const std::vector<FacadeStyle> styles = {
        {"facade-brick", 256, 256, 4, 4, 3.6}, {"facade-plaster", 192, 160, 3, 2, 3.8},
        {"facade-glass", 512, 256, 8, 4, 3.0}, {"facade-concrete", 128, 256, 2, 4, 3.4},
        {"facade-stone", 96, 96, 1, 1, 4.0},   {"facade-modern", 320, 200, 5, 3, 3.2},
    };
    return styles;
}

osg::ref_ptr<osg::Image> CityTextures::generateFacade(const FacadeStyle& s)
{
    Canvas c(s.name, s.width, s.height);
    const int cw = s.width / s.bays, ch = s.height / s.floors;
    if (s.name == "facade-brick")
    {
        c.fillNoise({150, 72, 52}, 10, 11);
        for (int y = 0; y < c.h(); y += 4) // mortar courses
            c.rect(0, y, c.w(), y + 1, {185, 170, 150}, 6, 12);
        for (int y = 0; y < c.h(); y += 4)
            for (int x = ((y / 4) % 2) * 4; x < c.w(); x += 8)
                c.rect(x, y, x + 1, y + 4, {185, 170, 150});
        for (int f = 0; f < s.floors; ++f)
            for (int b = 0; b < s.bays; ++b)
                drawWindow(c, b * cw, f * ch, cw, ch, 0.5, 0.55, {235, 232, 225}, {50, 65, 85}, 13);
    }
    else if (s.name == "facade-plaster")
    {
        c.fillNoise({214, 196, 160}, 7, 21);
        for (int f = 0; f < s.floors; ++f)
        {
            c.rect(0, f * ch, c.w(), f * ch + 3, {190, 172, 138}); // cornice per storey
            for (int b = 0; b < s.bays; ++b)
                drawWindow(c, b * cw, f * ch, cw, ch, 0.42, 0.58, {120, 90, 60}, {45, 55, 70}, 23);
        }
    }
    else if (s.name == "facade-glass")
    {
        c.fillNoise({70, 95, 120}, 5, 31);
        for (int f = 0; f < s.floors; ++f)
            for (int b = 0; b < s.bays; ++b)
            {
                const int x0 = b * cw, y0 = f * ch;
                for (int y = y0; y < y0 + ch; ++y)
                    for (int x = x0; x < x0 + cw; ++x)
                    {
                        const int sky = (y - y0) * 60 / ch + noise(b, f, 32, 12);
                        c.set(x, y, {80 + sky, 110 + sky, 140 + sky});
                    }
                c.rect(x0, y0, x0 + 2, y0 + ch, {40, 45, 50});      // vertical mullion
                c.rect(x0, y0, x0 + cw, y0 + ch / 6, {55, 60, 66}); // spandrel
            }
    }
    else if (s.name == "facade-concrete")
    {
        c.fillNoise({160, 160, 155}, 9, 41);
        for (int f = 0; f < s.floors; ++f)
            for (int b = 0; b < s.bays; ++b)
            {
                c.rect(b * cw, f * ch, b * cw + cw, f * ch + 1, {120, 120, 118}); // panel joints
                c.rect(b * cw, f * ch, b * cw + 1, f * ch + ch, {120, 120, 118});
                drawWindow(c, b * cw, f * ch, cw, ch, 0.62, 0.45, {90, 90, 90}, {40, 50, 60}, 43);
            }
    }
    else if (s.name == "facade-stone")
    {
        c.fillNoise({196, 180, 140}, 12, 51);
        for (int y = 0; y < c.h(); y += 12)
            c.rect(0, y, c.w(), y + 1, {150, 136, 100});
        // One tall arched window per tile.
        const int ww = cw / 2, x0 = (cw - ww) / 2, y0 = ch / 8, wh = ch * 5 / 8;
        for (int y = y0; y < y0 + wh + ww / 2; ++y)
            for (int x = x0; x < x0 + ww; ++x)
            {
                const double dx = x - (x0 + ww / 2.0), dy = y - (y0 + wh);
                if (y < y0 + wh || dx * dx + dy * dy <= (ww / 2.0) * (ww / 2.0))
                    c.set(x, y, {40 + (y - y0) / 3, 48 + (y - y0) / 3, 60 + (y - y0) / 3});
            }
    }
    else // facade-modern: white bands with ribbon windows
    {
        c.fillNoise({232, 232, 228}, 4, 61);
        for (int f = 0; f < s.floors; ++f)
        {
            const int y0 = f * ch + ch / 4, y1 = f * ch + ch * 3 / 4;
            for (int y = y0; y < y1; ++y)
                for (int x = 0; x < c.w(); ++x)
                    c.set(x, y, {35 + (y - y0), 60 + (y - y0), 80 + (y - y0)});
            for (int b = 0; b < s.bays; ++b)
                c.rect(b * cw, y0, b * cw + 2, y1, {200, 200, 200});
        }
    }
    return c.image();
}

osg::ref_ptr<osg::Image> CityTextures::generateSurface(const std::string& kind)
{
    if (kind == "roof-gravel")
    {
        Canvas c(kind, 128, 128);
        c.fillNoise({118, 116, 112}, 22, 71);
        return c.image();
    }
    if (kind == "roof-tiles")
    {
        Canvas c(kind, 64, 64);
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 64; ++x)
            {
                const int row = y / 8, shade = (y % 8) * 6 - ((x + row * 4) % 8 == 0 ? 40 : 0);
                c.set(x, y, {150 + shade + noise(x, y, 72, 8), 60 + shade / 2, 45});
            }
        return c.image();
    }
    if (kind == "terrain" || kind == "park-grass" || kind == "forest-floor")
    {
        const Rgb base = kind == "terrain"      ? Rgb{118, 132, 78}
                         : kind == "park-grass" ? Rgb{86, 150, 64}
                                                : Rgb{64, 84, 44};
        Canvas c(kind, 256, 256);
        const int seed = kind == "terrain" ? 81 : kind == "park-grass" ? 82 : 83;
        for (int y = 0; y < 256; ++y)
            for (int x = 0; x < 256; ++x)
            {
                // Two octaves: blotches (8 px cells, smoothed by averaging corners) plus grain.
                const int bx = x / 16, by = y / 16;
                const int blotch = (noise(bx, by, seed, 14) + noise(bx + 1, by, seed, 14) +
                                    noise(bx, by + 1, seed, 14) + noise(bx + 1, by + 1, seed, 14)) /
                                   2;
                const int grain = noise(x, y, seed + 100, 12);
                c.set(x, y,
                      {base.r + blotch + grain, base.g + blotch + grain, base.b + blotch / 2 + grain / 2});
            }
        return c.image();
    }
    if (kind == "road-minor" || kind == "road-major")
    {
        const bool major = kind == "road-major";
        Canvas c(kind, 128, 128);
        c.fillNoise(major ? Rgb{62, 62, 66} : Rgb{84, 84, 86}, 10, major ? 91 : 92);
        // u runs across the road, v along it.
        c.rect(0, 0, 3, 128, {150, 150, 150}); // kerbs
        c.rect(125, 0, 128, 128, {150, 150, 150});
        if (major)
        {
            c.rect(61, 0, 63, 128, {225, 205, 90}); // double yellow centre line
            c.rect(65, 0, 67, 128, {225, 205, 90});
            c.rect(32, 0, 34, 64, {230, 230, 230}); // dashed lane lines
            c.rect(94, 0, 96, 64, {230, 230, 230});
        }
        else
            c.rect(63, 0, 65, 56, {230, 230, 230}); // dashed centre line
        return c.image();
    }
    if (kind == "water")
    {
        Canvas c(kind, 128, 128);
        for (int y = 0; y < 128; ++y)
            for (int x = 0; x < 128; ++x)
            {
                const double wave = std::sin((x * 2 + y) * 0.19) * std::sin((y * 3 - x) * 0.11);
                const int n = static_cast<int>(std::lround(wave * 14.0)) + noise(x, y, 101, 4);
                c.set(x, y, {42 + n, 92 + n, 140 + n});
            }
        return c.image();
    }
    throw std::invalid_argument("unknown city texture kind '" + kind + "'");
}

osg::ref_ptr<osg::Texture2D> CityTextures::makeTexture(osg::Image* image)
{
    osg::ref_ptr<osg::Texture2D> t = new osg::Texture2D(image);
    t->setName(image->getName());
    t->setWrap(osg::Texture::WRAP_S, osg::Texture::REPEAT);
    t->setWrap(osg::Texture::WRAP_T, osg::Texture::REPEAT);
    t->setFilter(osg::Texture::MIN_FILTER, osg::Texture::LINEAR_MIPMAP_LINEAR);
    t->setFilter(osg::Texture::MAG_FILTER, osg::Texture::LINEAR);
    t->setResizeNonPowerOfTwoHint(false);
    t->setUseHardwareMipMapGeneration(true);
    t->setUnRefImageDataAfterApply(false);
    return t;
}

} // namespace osgLoA
