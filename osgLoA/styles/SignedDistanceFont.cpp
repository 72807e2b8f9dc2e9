// SignedDistanceFont: Green's (2007) signed distance fields of a font's glyphs, in one atlas.
#include <osgLoA/interest/DistanceField>
#include <osgLoA/styles/SignedDistanceFont>

#include <osgDB/FileUtils>
#include <osgText/Font>
#include <osgText/String>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace osgLoA
{

SignedDistanceFont::SignedDistanceFont(const std::string& fontFile, const Parameters& p)
    : _parameters(p), _file(fontFile)
{
    if (p.renderPixels < 8 || p.renderPixels > 512)
        throw std::invalid_argument("signed distance font: renderPixels " + std::to_string(p.renderPixels) +
                                    " is outside 8..512");
    if (p.downsample < 1 || p.downsample > 16)
        throw std::invalid_argument("signed distance font: downsample " + std::to_string(p.downsample) +
                                    " is outside 1..16");
    if (p.spread < 1 || p.spread > 32)
        throw std::invalid_argument("signed distance font: spread " + std::to_string(p.spread) +
                                    " is outside 1..32");
    if (fontFile.empty()) throw std::runtime_error("signed distance font: no font file given");
    // osgText falls back to its built-in font for a file it cannot find: refuse that here.
    if (!osgDB::fileExists(fontFile) && osgDB::findDataFile(fontFile).empty())
        throw std::runtime_error("signed distance font: the font file '" + fontFile + "' does not exist");
    _font = osgText::readRefFontFile(fontFile);
    if (!_font.valid())
        throw std::runtime_error("signed distance font: cannot read the font file '" + fontFile +
                                 "' (osgdb_freetype)");
    _atlas = new osg::Image;
    _texture = new osg::Texture2D;
    _texture->setName("osgLoA.SignedDistanceFont.atlas");
    _texture->setFilter(osg::Texture::MIN_FILTER, osg::Texture::LINEAR_MIPMAP_LINEAR);
    _texture->setFilter(osg::Texture::MAG_FILTER, osg::Texture::LINEAR);
    _texture->setWrap(osg::Texture::WRAP_S, osg::Texture::CLAMP_TO_EDGE);
    _texture->setWrap(osg::Texture::WRAP_T, osg::Texture::CLAMP_TO_EDGE);
    _texture->setResizeNonPowerOfTwoHint(false);
    _texture->setUnRefImageDataAfterApply(false);
    // The cap height centres labels on their line.
    const osgText::FontResolution res(unsigned(p.renderPixels), unsigned(p.renderPixels));
    if (osgText::Glyph* h = _font->getGlyph(res, 'H')) _capHeight = h->getHeight();
    // FreeType answers a code point the font lacks with its .notdef glyph (a box): remembered from a
    // private-use code point no font maps, so that require() can tell it.
    _notdef = _font->getGlyph(res, 0x10FFFDu);
}

bool SignedDistanceFont::isNotdef(const osg::Image& glyph) const
{
    if (!_notdef.valid() || &glyph == _notdef.get()) return _notdef.valid();
    if (glyph.s() != _notdef->s() || glyph.t() != _notdef->t()) return false;
    if (glyph.getTotalSizeInBytes() != _notdef->getTotalSizeInBytes()) return false;
    return glyph.getTotalSizeInBytes() == 0 ||
           std::equal(glyph.data(), glyph.data() + glyph.getTotalSizeInBytes(), _notdef->data());
}

SignedDistanceFont::SignedDistanceFont(const std::string& fontFile)
    : SignedDistanceFont(fontFile, Parameters())
{
}

SignedDistanceFont::~SignedDistanceFont() = default;

std::string SignedDistanceFont::defaultFontFile()
{
    if (const char* env = std::getenv("LOA_LABEL_FONT"))
        if (*env) return env;
    const std::string found = osgDB::findDataFile("fonts/DejaVuSans-Bold.ttf");
    if (!found.empty()) return found;
    const char* const candidates[] = {"/usr/share/fonts/truetype/dejavu/DejaVuSans-Bold.ttf",
                                      "/usr/share/fonts/dejavu/DejaVuSans-Bold.ttf"};
    for (const char* c : candidates)
        if (osgDB::fileExists(c)) return c;
    return std::string();
}

std::vector<unsigned> SignedDistanceFont::decodeUtf8(const std::string& text)
{
    const osgText::String s(text, osgText::String::ENCODING_UTF8);
    return std::vector<unsigned>(s.begin(), s.end());
}

std::vector<float> SignedDistanceFont::signedDistance(const std::vector<unsigned char>& inside, int width,
                                                      int height, int downsample, int spread, int& fieldWidth,
                                                      int& fieldHeight)
{
    if (width < 0 || height < 0 || inside.size() != std::size_t(width) * std::size_t(height))
        throw std::invalid_argument("signed distance: the mask is not width x height");
    if (downsample < 1 || spread < 1)
        throw std::invalid_argument("signed distance: downsample and spread must be at least 1");
    const int margin = spread * downsample;
    // The field covers the mask and spread field texels around it.
    fieldWidth = (width + downsample - 1) / downsample + 2 * spread;
    fieldHeight = (height + downsample - 1) / downsample + 2 * spread;
    const int W = fieldWidth * downsample, H = fieldHeight * downsample; // padded high-res grid
    if (W > DistanceField::kMaxResolution || H > DistanceField::kMaxResolution)
        throw std::invalid_argument("signed distance: the glyph is too large");
    DistanceField::Seeds in(W, H), out(W, H);
    bool any = false;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
        {
            const int mx = x - margin, my = y - margin;
            const bool v = mx >= 0 && my >= 0 && mx < width && my < height &&
                           inside[std::size_t(my) * std::size_t(width) + std::size_t(mx)] != 0;
            any = any || v;
            in.set(x, y, v);
            out.set(x, y, !v);
        }
    std::vector<float> field(std::size_t(fieldWidth) * std::size_t(fieldHeight), -float(spread + 1));
    if (!any) return field;
    const DistanceField::Map toInside = DistanceField::computeExact(in);
    const DistanceField::Map toOutside = DistanceField::computeExact(out);
    const float scale = 1.0f / float(downsample);
    for (int j = 0; j < fieldHeight; ++j)
        for (int i = 0; i < fieldWidth; ++i)
        {
            // The high-resolution texel at the field texel's centre (the centre of its block:
            // exact for an odd downsample, half a texel off for an even one).
            const int x = i * downsample + downsample / 2, y = j * downsample + downsample / 2;
            const float d = in.isSeed(x, y) ? toOutside.at(x, y) - 0.5f : -(toInside.at(x, y) - 0.5f);
            field[std::size_t(j) * std::size_t(fieldWidth) + std::size_t(i)] = d * scale;
        }
    return field;
}

void SignedDistanceFont::require(const std::vector<unsigned>& codes)
{
    const osgText::FontResolution res(unsigned(_parameters.renderPixels), unsigned(_parameters.renderPixels));
    bool added = false;
    for (unsigned code : codes)
    {
        if (_glyphs.count(code)) continue;
        Glyph g;
        g.code = code;
        osgText::Glyph* src = _font->getGlyph(res, code);
        if (!src || (code != 0x10FFFDu && isNotdef(*src)))
        {
            ++_missing;
            g.advance = 0.5f;
            _glyphs[code] = g;
            continue;
        }
        g.advance = src->getHorizontalAdvance();
        const int w = src->s(), h = src->t();
        if (w > 0 && h > 0 && src->data())
        {
            std::vector<unsigned char> mask(std::size_t(w) * std::size_t(h));
            // GL_ALPHA, one byte per texel, rows packed (osgText's freetype glyphs), row 0 lowest.
            for (int y = 0; y < h; ++y)
            {
                const unsigned char* row = src->data(0, y);
                for (int x = 0; x < w; ++x)
                    mask[std::size_t(y) * std::size_t(w) + std::size_t(x)] = row[x] >= 128 ? 1 : 0;
            }
            Field f;
            const std::vector<float> d =
                signedDistance(mask, w, h, _parameters.downsample, _parameters.spread, f.width, f.height);
            f.values.resize(d.size());
            const float spread = float(_parameters.spread);
            for (std::size_t k = 0; k < d.size(); ++k)
            {
                const float v = 0.5f + 0.5f * std::max(-1.0f, std::min(1.0f, d[k] / spread));
                f.values[k] = static_cast<unsigned char>(std::lround(v * 255.0f));
            }
            // The quad: the mask's lower-left is the glyph's bearing (em); the field starts
            // spread texels (spread downsample pixels) before it.
            const float em = float(_parameters.renderPixels);
            const osg::Vec2f bearing = src->getHorizontalBearing();
            const float margin = float(_parameters.spread * _parameters.downsample) / em;
            g.quadMin = bearing - osg::Vec2f(margin, margin);
            g.quadMax = g.quadMin + osg::Vec2f(float(f.width * _parameters.downsample) / em,
                                               float(f.height * _parameters.downsample) / em);
            g.blank = false;
            _fields[code] = std::move(f);
        }
        _glyphs[code] = g;
        added = true;
    }
    if (added) rebuildAtlas();
}

void SignedDistanceFont::rebuildAtlas()
{
    // Shelf packing in code-point order, rows of at most 1024 texels, one texel of gap.
    const int maxWidth = 1024, gap = 1;
    int x = gap, y = gap, rowHeight = 0, width = 0;
    std::map<unsigned, std::pair<int, int>> at;
    for (const auto& kv : _fields)
    {
        const Field& f = kv.second;
        if (x + f.width + gap > maxWidth)
        {
            x = gap;
            y += rowHeight + gap;
            rowHeight = 0;
        }
        at[kv.first] = std::make_pair(x, y);
        x += f.width + gap;
        width = std::max(width, x);
        rowHeight = std::max(rowHeight, f.height);
    }
    const int height = std::max(1, y + rowHeight + gap);
    width = std::max(1, width);
    _atlas->allocateImage(width, height, 1, GL_RED, GL_UNSIGNED_BYTE, 1);
    _atlas->setInternalTextureFormat(GL_R8);
    std::fill(_atlas->data(), _atlas->data() + _atlas->getTotalSizeInBytes(), 0);
    for (const auto& kv : _fields)
    {
        const Field& f = kv.second;
        const std::pair<int, int> p = at[kv.first];
        for (int r = 0; r < f.height; ++r)
            std::copy(f.values.begin() + std::ptrdiff_t(r) * f.width,
                      f.values.begin() + std::ptrdiff_t(r + 1) * f.width,
                      _atlas->data(p.first, p.second + r));
        Glyph& g = _glyphs[kv.first];
        g.texMin = osg::Vec2f(float(p.first) / float(width), float(p.second) / float(height));
        g.texMax =
            osg::Vec2f(float(p.first + f.width) / float(width), float(p.second + f.height) / float(height));
    }
    _atlas->dirty();
    _texture->setImage(_atlas.get());
}

const SignedDistanceFont::Glyph* SignedDistanceFont::glyph(unsigned code) const
{
    const auto it = _glyphs.find(code);
    return it == _glyphs.end() ? nullptr : &it->second;
}

float SignedDistanceFont::kerning(unsigned left, unsigned right) const
{
    const auto key = std::make_pair(left, right);
    const auto found = _kerning.find(key);
    if (found != _kerning.end()) return found->second;
    const osgText::FontResolution res(unsigned(_parameters.renderPixels), unsigned(_parameters.renderPixels));
    const float k = _font->getKerning(res, left, right, osgText::KERNING_DEFAULT).x();
    _kerning.emplace(key, k);
    return k;
}

} // namespace osgLoA
