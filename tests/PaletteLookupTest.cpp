// Tests of the palette lookup of paper 003 without GL: PaletteLookup (nearest palette colour in
// CIELab, segmented textures) against hand-computed values, TexturePalette (build, disk cache,
// lookup texture, serializer round trip), PaletteMapping::attach on a scene (CPU weights) and the
// "palette" graphic style's registration.
#include <osgLoA/palette/PaletteLookup>
#include <osgLoA/palette/PaletteMapping>
#include <osgLoA/palette/PaletteStyle>
#include <osgLoA/palette/TexturePalette>
#include <osgLoA/palette/WeightedColor>
#include <osgLoA/styles/GraphicStyleCatalog>

#include "support/TestSupport.h"

#include <osg/Geode>
#include <osg/Geometry>
#include <osg/Texture2D>
#include <osg/UserDataContainer>
#include <osgDB/ReadFile>
#include <osgDB/WriteFile>

#include <algorithm>

#include <gtest/gtest.h>

#include <cstring>
#include <set>

using namespace osgLoA;

namespace
{
/** A K x K RGBA8 palette image; rows[k - 1] holds level k's colours (the rest of the row
 *  repeats the last one, as PaletteTexture does). */
osg::ref_ptr<osg::Image> handPalette(const std::vector<std::vector<osg::Vec3ub>>& rows)
{
    const int K = int(rows.size());
    osg::ref_ptr<osg::Image> img = new osg::Image;
    img->allocateImage(K, K, 1, GL_RGBA, GL_UNSIGNED_BYTE, 1);
    for (int y = 0; y < K; ++y)
        for (int x = 0; x < K; ++x)
        {
            const osg::Vec3ub& c = rows[y][std::min<std::size_t>(x, rows[y].size() - 1)];
            unsigned char* p = img->data(x, y);
            p[0] = c[0];
            p[1] = c[1];
            p[2] = c[2];
            p[3] = 255;
        }
    return img;
}

osg::ref_ptr<osg::Image> rgbaImage(int w, int h, const std::vector<osg::Vec4ub>& texels)
{
    osg::ref_ptr<osg::Image> img = new osg::Image;
    img->allocateImage(w, h, 1, GL_RGBA, GL_UNSIGNED_BYTE, 1);
    for (int i = 0; i < w * h; ++i)
        std::memcpy(img->data(i % w, i / w), texels[i].ptr(), 4);
    return img;
}

/** 4x4 texture of 5 distinct colours (alpha varies), and per-texel weights. */
osg::ref_ptr<osg::Image> smallTexture()
{
    const osg::Vec4ub c[5] = {
        {200, 40, 30, 255}, {30, 160, 60, 200}, {40, 70, 210, 255}, {230, 220, 80, 100}, {20, 20, 24, 255}};
    std::vector<osg::Vec4ub> t;
    for (int i = 0; i < 16; ++i)
        t.push_back(c[(i * 3) % 5]);
    return rgbaImage(4, 4, t);
}

std::vector<double> smallWeights()
{
    std::vector<double> w;
    for (int i = 0; i < 16; ++i)
        w.push_back(1.0 + (i % 4));
    return w;
}

bool sameImage(const osg::Image& a, const osg::Image& b)
{
    return a.s() == b.s() && a.t() == b.t() && a.getPixelFormat() == b.getPixelFormat() &&
           a.getTotalSizeInBytes() == b.getTotalSizeInBytes() &&
           std::memcmp(a.data(), b.data(), a.getTotalSizeInBytes()) == 0;
}

const osg::Vec3ub kRed(255, 0, 0), kGreen(0, 255, 0), kBlue(0, 0, 255), kGrey(128, 128, 128);
} // namespace

TEST(PaletteLookupTest, ClosestIsTheNearestColourInLabNotInRgb)
{
    osg::ref_ptr<osg::Image> p = handPalette({{kGrey}, {kRed, kBlue}, {kRed, kGreen, kBlue}});
    // Obvious cases.
    EXPECT_EQ(PaletteLookup::closest(*p, 3, osg::Vec3f(0.9f, 0.1f, 0.1f)), 0u);
    EXPECT_EQ(PaletteLookup::closest(*p, 3, osg::Vec3f(0.1f, 0.8f, 0.2f)), 1u);
    EXPECT_EQ(PaletteLookup::closest(*p, 3, osg::Vec3f(0.1f, 0.1f, 0.7f)), 2u);
    // Yellow is as far from red as from green in RGB; in Lab (by hand: yellow (97.1, -21.6, 94.5),
    // red (53.2, 80.1, 67.2), green (87.7, -86.2, 83.2)) dE^2 is 13015 to red and 4389 to green.
    EXPECT_EQ(PaletteLookup::closest(*p, 3, osg::Vec3f(1, 1, 0)), 1u);
    // Magenta (60.3, 98.2, -60.8): 16762 to red, 3363 to blue (blue (32.3, 79.2, -107.9)).
    EXPECT_EQ(PaletteLookup::closest(*p, 3, osg::Vec3f(1, 0, 1)), 2u);
    EXPECT_EQ(PaletteLookup::closest(*p, 2, osg::Vec3f(1, 0, 1)), 1u);
    // Level 1 has one colour; map returns the palette texel / 255.
    EXPECT_EQ(PaletteLookup::closest(*p, 1, osg::Vec3f(1, 0, 1)), 0u);
    EXPECT_EQ(PaletteLookup::map(*p, 1, osg::Vec3f(1, 0, 1)), osg::Vec3f(128, 128, 128) / 255.0f);
    EXPECT_EQ(PaletteLookup::map(*p, 3, osg::Vec3f(1, 1, 0)), osg::Vec3f(0, 1, 0));
    // Ties go to the lower index.
    osg::ref_ptr<osg::Image> tie = handPalette({{kRed}, {kBlue, kBlue}});
    EXPECT_EQ(PaletteLookup::closest(*tie, 2, osg::Vec3f(0, 0, 1)), 0u);
    // Bad input.
    EXPECT_THROW(PaletteLookup::closest(*p, 0, osg::Vec3f()), std::invalid_argument);
    EXPECT_THROW(PaletteLookup::closest(*p, 4, osg::Vec3f()), std::invalid_argument);
    osg::ref_ptr<osg::Image> notSquare = new osg::Image;
    notSquare->allocateImage(3, 2, 1, GL_RGBA, GL_UNSIGNED_BYTE);
    EXPECT_THROW(PaletteLookup::closest(*notSquare, 1, osg::Vec3f()), std::invalid_argument);
}

TEST(PaletteLookupTest, SegmentAtOneColourIsTheWeightedMeanAndAtAllColoursTheTexture)
{
    osg::ref_ptr<osg::Image> tex = smallTexture();
    const std::vector<double> w = smallWeights();
    osg::ref_ptr<TexturePalette> pal = TexturePalette::build(*tex, w);
    ASSERT_EQ(pal->getLevels(), 5u);
    const osg::Image& palette = *pal->getPaletteImage();
    // The weighted Lab mean of the texels, computed here: every texel is one sample of weight w.
    osg::Vec3d sum;
    double total = 0.0;
    for (int i = 0; i < 16; ++i)
    {
        const unsigned char* p = tex->data(i % 4, i / 4);
        sum += osg::Vec3d(WeightedColor::toLab(osg::Vec3f(p[0], p[1], p[2]) / 255.0f)) * w[i];
        total += w[i];
    }
    const osg::Vec3f mean = WeightedColor::fromLab(osg::Vec3f(sum / total)) * 255.0f;
    osg::ref_ptr<osg::Image> one = PaletteLookup::segment(*tex, palette, 1);
    std::set<unsigned> colours;
    for (int i = 0; i < 16; ++i)
    {
        const unsigned char* q = one->data(i % 4, i / 4);
        colours.insert(q[0] << 16 | q[1] << 8 | q[2]);
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(q[c], mean[c], 0.5001) << "texel " << i << " channel " << c;
        EXPECT_EQ(q[3], tex->data(i % 4, i / 4)[3]) << "alpha kept";
    }
    EXPECT_EQ(colours.size(), 1u);
    // All 5 colours: the texture itself, byte for byte.
    osg::ref_ptr<osg::Image> all = PaletteLookup::segment(*tex, palette, 5);
    EXPECT_TRUE(sameImage(*all, *tex));
    // Each level k has at most k colours.
    for (unsigned k = 1; k <= 5; ++k)
    {
        osg::ref_ptr<osg::Image> s = PaletteLookup::segment(*tex, palette, k);
        std::set<unsigned> n;
        for (int i = 0; i < 16; ++i)
            n.insert(s->data(i % 4, i / 4)[0] << 16 | s->data(i % 4, i / 4)[1] << 8 |
                     s->data(i % 4, i / 4)[2]);
        EXPECT_LE(n.size(), k);
    }
    osg::ref_ptr<osg::Image> lum = new osg::Image;
    lum->allocateImage(4, 4, 1, GL_LUMINANCE, GL_UNSIGNED_BYTE);
    EXPECT_THROW(PaletteLookup::segment(*lum, palette, 1), std::invalid_argument);
}

TEST(PaletteLookupTest, TexturePaletteBuildLevelsAndLookupTexture)
{
    osg::ref_ptr<osg::Image> tex = smallTexture();
    std::vector<double> w = smallWeights();
    EXPECT_THROW(TexturePalette::build(*tex, w, PaletteHierarchy::WARD, 0), std::invalid_argument);
    EXPECT_THROW(TexturePalette::build(*tex, std::vector<double>(16, 0.0)), std::invalid_argument);
    EXPECT_THROW(TexturePalette::build(*tex, std::vector<double>(15, 1.0)), std::invalid_argument);
    osg::ref_ptr<TexturePalette> three = TexturePalette::build(*tex, w, PaletteHierarchy::CENTROID, 3);
    EXPECT_EQ(three->getLevels(), 3u);
    EXPECT_EQ(three->getHierarchy()->numColors(), 5u);
    EXPECT_EQ(three->getHierarchy()->getLinkage(), PaletteHierarchy::CENTROID);
    EXPECT_EQ(three->getPaletteImage()->s(), 3);
    // The lookup texture holds the Lab of each palette image texel.
    osg::Texture2D* lookup = three->getLookupTexture();
    ASSERT_TRUE(lookup);
    EXPECT_EQ(lookup->getInternalFormat(), GLint(GL_RGBA32F_ARB));
    EXPECT_EQ(lookup->getFilter(osg::Texture::MIN_FILTER), osg::Texture::NEAREST);
    const osg::Image* lab = lookup->getImage();
    ASSERT_EQ(lab->s(), 3);
    ASSERT_EQ(lab->getDataType(), GLenum(GL_FLOAT));
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 3; ++x)
        {
            const unsigned char* p = three->getPaletteImage()->data(x, y);
            const osg::Vec3f expected = WeightedColor::toLab(osg::Vec3f(p[0], p[1], p[2]) / 255.0f);
            const float* q = reinterpret_cast<const float*>(lab->data(x, y));
            EXPECT_EQ(osg::Vec3f(q[0], q[1], q[2]), expected);
            EXPECT_EQ(q[3], 1.0f);
        }
    // A setter rebuilds the derived texture.
    three->setLevels(5);
    EXPECT_EQ(three->getLookupTexture()->getImage()->s(), 5);
    osg::ref_ptr<TexturePalette> empty = new TexturePalette;
    EXPECT_THROW(empty->getPaletteImage(), std::logic_error);
}

TEST(PaletteLookupTest, TexturePaletteDiskCache)
{
    const std::string dir = loatest::freshDirectory("PaletteLookupTest-cache");
    osg::ref_ptr<osg::Image> tex = smallTexture();
    std::vector<double> w = smallWeights();
    osg::ref_ptr<TexturePalette> a = TexturePalette::buildCached(*tex, w, PaletteHierarchy::WARD, 256, dir);
    EXPECT_FALSE(a->getFromCache());
    ASSERT_TRUE(a->getHierarchy());
    osg::ref_ptr<TexturePalette> b = TexturePalette::buildCached(*tex, w, PaletteHierarchy::WARD, 256, dir);
    EXPECT_TRUE(b->getFromCache());
    EXPECT_FALSE(b->getHierarchy());
    EXPECT_EQ(b->getLevels(), 5u);
    EXPECT_TRUE(sameImage(*a->getPaletteImage(), *b->getPaletteImage()));
    // Other weights, linkage or K: other keys, misses.
    w[3] = 7.0;
    EXPECT_FALSE(TexturePalette::buildCached(*tex, w, PaletteHierarchy::WARD, 256, dir)->getFromCache());
    EXPECT_FALSE(TexturePalette::buildCached(*tex, w, PaletteHierarchy::CENTROID, 256, dir)->getFromCache());
    EXPECT_FALSE(TexturePalette::buildCached(*tex, w, PaletteHierarchy::WARD, 4, dir)->getFromCache());
    EXPECT_TRUE(TexturePalette::buildCached(*tex, w, PaletteHierarchy::WARD, 4, dir)->getFromCache());
    // Same colour table, other texel layout (texels 0 and 5 have one colour; their weights
    // swapped): another key.
    std::vector<double> swapped = smallWeights();
    std::swap(swapped[0], swapped[5]);
    ASSERT_EQ(tex->data(0, 0)[0], tex->data(1, 1)[0]);
    ASSERT_NE(swapped[0], swapped[5]);
    EXPECT_NE(TexturePalette::cacheKey(*tex, swapped, PaletteHierarchy::WARD, 256),
              TexturePalette::cacheKey(*tex, smallWeights(), PaletteHierarchy::WARD, 256));
    // No directory: plain build.
    EXPECT_FALSE(TexturePalette::buildCached(*tex, w, PaletteHierarchy::WARD, 256, "")->getFromCache());
}

TEST(PaletteLookupTest, TexturePaletteSerializerRoundTrip)
{
    const std::string dir = loatest::freshDirectory("PaletteLookupTest-serializer");
    osg::ref_ptr<osg::Image> tex = smallTexture();
    osg::ref_ptr<TexturePalette> built =
        TexturePalette::build(*tex, smallWeights(), PaletteHierarchy::WARD, 4);
    built->setName("small");
    osg::ref_ptr<TexturePalette> imageOnly = new TexturePalette;
    imageOnly->setStoredImage(const_cast<osg::Image*>(built->getPaletteImage()));
    for (TexturePalette* original : {built.get(), imageOnly.get()})
        for (const char* ext : {"osgt", "osgb"})
        {
            const bool withHierarchy = original->getHierarchy() != nullptr;
            SCOPED_TRACE(std::string(withHierarchy ? "hierarchy " : "image ") + ext);
            const std::string tag = std::string(withHierarchy ? "h" : "i") + "." + ext;
            const std::string first = dir + "/first-" + tag, second = dir + "/second-" + tag;
            ASSERT_TRUE(osgDB::writeObjectFile(*original, first));
            osg::ref_ptr<TexturePalette> back =
                dynamic_cast<TexturePalette*>(osgDB::readRefObjectFile(first).get());
            ASSERT_TRUE(back.valid());
            EXPECT_EQ(back->getName(), original->getName());
            EXPECT_EQ(back->getLevels(), 4u);
            EXPECT_EQ(back->getHierarchy() != nullptr, withHierarchy);
            if (withHierarchy)
            {
                EXPECT_EQ(back->getHierarchy()->numColors(), 5u);
            }
            // The hierarchy is written to 6 digits in text; the 8-bit palette survives exactly.
            EXPECT_TRUE(sameImage(*back->getPaletteImage(), *original->getPaletteImage()));
            ASSERT_TRUE(osgDB::writeObjectFile(*back, second));
            EXPECT_EQ(loatest::fileBytes(first), loatest::fileBytes(second));
        }
    const std::string text = loatest::fileBytes(dir + "/first-i.osgt");
    EXPECT_NE(text.find("PaletteImage 4"), std::string::npos) << text;
    EXPECT_EQ(loatest::fileBytes(dir + "/first-h.osgt").find("PaletteImage"), std::string::npos);
}

namespace
{
osg::ref_ptr<osg::Geometry> texturedQuad(float x0, bool texCoords = true)
{
    osg::ref_ptr<osg::Geometry> g = new osg::Geometry;
    osg::ref_ptr<osg::Vec3Array> v = new osg::Vec3Array;
    osg::ref_ptr<osg::Vec2Array> t = new osg::Vec2Array;
    for (auto p : {osg::Vec2(0, 0), osg::Vec2(1, 0), osg::Vec2(1, 1), osg::Vec2(0, 1)})
    {
        v->push_back(osg::Vec3(x0 + p.x(), p.y(), 0));
        t->push_back(p);
    }
    g->setVertexArray(v.get());
    if (texCoords) g->setTexCoordArray(0, t.get(), osg::Array::BIND_PER_VERTEX);
    g->addPrimitiveSet(new osg::DrawArrays(GL_QUADS, 0, 4));
    return g;
}
} // namespace

TEST(PaletteLookupTest, AttachPutsOnePalettePerTextureOnItsStateSets)
{
    osg::ref_ptr<osg::Texture2D> a = new osg::Texture2D(smallTexture().get());
    osg::ref_ptr<osg::Image> other = rgbaImage(2, 1, {{10, 20, 30, 255}, {200, 100, 0, 255}});
    osg::ref_ptr<osg::Texture2D> b = new osg::Texture2D(other.get());
    osg::ref_ptr<osg::Image> unused = rgbaImage(1, 1, {{1, 2, 3, 255}});
    osg::ref_ptr<osg::Texture2D> c = new osg::Texture2D(unused.get());
    osg::ref_ptr<osg::Group> root = new osg::Group;
    osg::ref_ptr<osg::Geode> g1 = new osg::Geode, g2 = new osg::Geode;
    g1->getOrCreateStateSet()->setTextureAttributeAndModes(0, a.get());
    g1->addDrawable(texturedQuad(0).get());
    osg::ref_ptr<osg::Geometry> q2 = texturedQuad(2);
    q2->getOrCreateStateSet()->setTextureAttributeAndModes(0, a.get()); // same image, other StateSet
    g2->addDrawable(q2.get());
    osg::ref_ptr<osg::Geometry> q3 = texturedQuad(4);
    q3->getOrCreateStateSet()->setTextureAttributeAndModes(0, b.get());
    g2->addDrawable(q3.get());
    osg::ref_ptr<osg::Geometry> q4 = texturedQuad(6, false); // no texture coordinates: no weights
    q4->getOrCreateStateSet()->setTextureAttributeAndModes(0, c.get());
    g2->addDrawable(q4.get());
    root->addChild(g1.get());
    root->addChild(g2.get());

    PaletteMapping::Options o;
    o.maxLevels = 3;
    EXPECT_EQ(PaletteMapping::attach(*root, o), 2u);
    bool hasPalette = true;
    ASSERT_TRUE(root->getStateSet()->getUniform("loa_hasPalette"));
    root->getStateSet()->getUniform("loa_hasPalette")->get(hasPalette);
    EXPECT_FALSE(hasPalette);
    TexturePalette* pa = PaletteMapping::paletteOf(*g1->getStateSet());
    ASSERT_TRUE(pa);
    EXPECT_EQ(PaletteMapping::paletteOf(*q2->getStateSet()), pa); // one palette per image
    TexturePalette* pb = PaletteMapping::paletteOf(*q3->getStateSet());
    ASSERT_TRUE(pb);
    EXPECT_NE(pa, pb);
    EXPECT_EQ(pa->getLevels(), 3u); // min(5 colours, maxLevels 3)
    EXPECT_EQ(pb->getLevels(), 2u); // 2 colours
    EXPECT_FALSE(PaletteMapping::paletteOf(*q4->getStateSet()));
    EXPECT_FALSE(q4->getStateSet()->getUniform("loa_hasPalette"));
    for (osg::StateSet* ss : {g1->getStateSet(), q2->getStateSet(), q3->getStateSet()})
    {
        int unit = -1, levels = -1;
        hasPalette = false;
        ss->getUniform("loa_paletteLookup")->get(unit);
        ss->getUniform("loa_paletteLevels")->get(levels);
        ss->getUniform("loa_hasPalette")->get(hasPalette);
        EXPECT_EQ(unit, int(PaletteMapping::kUnit));
        EXPECT_EQ(levels, ss == q3->getStateSet() ? 2 : 3);
        EXPECT_TRUE(hasPalette);
        EXPECT_EQ(ss->getTextureAttribute(PaletteMapping::kUnit, osg::StateAttribute::TEXTURE),
                  PaletteMapping::paletteOf(*ss)->getLookupTexture());
    }
    // Uniform weights over the quad (the whole texture, each texel the same area), so the
    // palette equals the one built from equal weights.
    osg::ref_ptr<TexturePalette> ref =
        TexturePalette::build(*a->getImage(), std::vector<double>(16, 1.0), PaletteHierarchy::WARD, 3);
    EXPECT_TRUE(sameImage(*ref->getPaletteImage(), *pa->getPaletteImage()));
    // Attaching again replaces, does not add, the stored palette.
    PaletteMapping::attach(*root, o);
    EXPECT_EQ(g1->getStateSet()->getUserDataContainer()->getNumUserObjects(), 1u);
    o.maxLevels = 0;
    EXPECT_THROW(PaletteMapping::attach(*root, o), std::invalid_argument);
}

// A luminance texture gets a palette of its greys; a texture in a format the palette path
// cannot read (RGTC) is skipped by name, the rest of the scene still gets its palettes.
TEST(PaletteLookupTest, AttachReadsLuminanceAndSkipsUnreadableFormatsByName)
{
    osg::ref_ptr<osg::Image> grey = new osg::Image;
    grey->allocateImage(2, 2, 1, GL_LUMINANCE, GL_UNSIGNED_BYTE);
    const unsigned char g[4] = {10, 10, 200, 90};
    std::copy(g, g + 4, grey->data());
    grey->setFileName("concrete.rgb");
    unsigned char blocks[8] = {0, 0, 0, 0, 0, 0, 0, 0};
    osg::ref_ptr<osg::Image> rgtc = new osg::Image;
    rgtc->setImage(4, 4, 1, GL_COMPRESSED_RED_RGTC1_EXT, GL_COMPRESSED_RED_RGTC1_EXT, GL_UNSIGNED_BYTE, blocks,
                   osg::Image::NO_DELETE);
    rgtc->setFileName("height.dds");
    osg::ref_ptr<osg::Geode> root = new osg::Geode;
    osg::ref_ptr<osg::Geometry> q1 = texturedQuad(0), q2 = texturedQuad(2);
    q1->getOrCreateStateSet()->setTextureAttributeAndModes(0, new osg::Texture2D(grey.get()));
    q2->getOrCreateStateSet()->setTextureAttributeAndModes(0, new osg::Texture2D(rgtc.get()));
    root->addDrawable(q1.get());
    root->addDrawable(q2.get());
    std::vector<std::string> skipped;
    PaletteMapping::Options o;
    o.skipped = &skipped;
    EXPECT_EQ(PaletteMapping::attach(*root, o), 1u);
    TexturePalette* p = PaletteMapping::paletteOf(*q1->getStateSet());
    ASSERT_TRUE(p);
    EXPECT_EQ(p->getLevels(), 3u); // greys 10, 200, 90
    const osg::Image* palette = p->getPaletteImage();
    for (int k = 0; k < palette->s(); ++k)
    {
        const unsigned char* c = palette->data(k, palette->t() - 1); // the finest level: the greys
        EXPECT_NEAR(int(c[0]), int(c[1]), 1);
        EXPECT_NEAR(int(c[1]), int(c[2]), 1);
    }
    EXPECT_FALSE(PaletteMapping::paletteOf(*q2->getStateSet()));
    ASSERT_EQ(skipped.size(), 1u);
    EXPECT_NE(skipped[0].find("palette: skipped texture 'height.dds'"), std::string::npos) << skipped[0];
    EXPECT_NE(skipped[0].find("0x8dbb"), std::string::npos) << skipped[0];
}

TEST(PaletteLookupTest, PaletteStyleIsInTheCatalog)
{
    ASSERT_TRUE(GraphicStyleCatalog::instance().contains("palette"));
    osg::ref_ptr<GraphicStyle> s = GraphicStyleCatalog::instance().create("palette");
    EXPECT_EQ(s->getFragmentShader(), "loa_style_palette.frag.glsl");
    EXPECT_TRUE(s->getUsesTexture());
    EXPECT_TRUE(s->getOpaque());
    const std::vector<std::pair<const char*, int>> ints = {
        {"loa_palette_strategy", 3}, {"loa_palette_level", 8},    {"loa_palette_levelNear", 32},
        {"loa_palette_levelFar", 4}, {"loa_palette_levelLow", 4}, {"loa_palette_levelHigh", 32}};
    for (const auto& [name, value] : ints)
    {
        int v = -1;
        ASSERT_TRUE(s->getParameter(name)) << name;
        s->getParameter(name)->get(v);
        EXPECT_EQ(v, value) << name;
    }
    float nearPlane = 0, farPlane = 0;
    s->getParameter("loa_palette_near")->get(nearPlane);
    s->getParameter("loa_palette_far")->get(farPlane);
    EXPECT_EQ(nearPlane, 50.0f);
    EXPECT_EQ(farPlane, 400.0f);
}

TEST(PaletteLookupTest, PalettesAreStoredWithTheModel)
{
    // attach() keeps each TexturePalette in its StateSet's user data: writing the model writes
    // them (osgdb_serializers_osgloa), and reading it back gives the same palette image.
    osg::ref_ptr<osg::Texture2D> a = new osg::Texture2D(smallTexture().get());
    osg::ref_ptr<osg::Geode> root = new osg::Geode;
    root->getOrCreateStateSet()->setTextureAttributeAndModes(0, a.get());
    root->addDrawable(texturedQuad(0).get());
    ASSERT_EQ(PaletteMapping::attach(*root), 1u);
    const TexturePalette* before = PaletteMapping::paletteOf(*root->getStateSet());
    ASSERT_TRUE(before);
    const std::string dir = loatest::freshDirectory("PalettesWithTheModel");
    for (const char* ext : {"osgb", "osgt"})
    {
        const std::string path = dir + "/model." + ext;
        ASSERT_TRUE(osgDB::writeNodeFile(*root, path)) << path;
        osg::ref_ptr<osg::Node> back = osgDB::readRefNodeFile(path);
        ASSERT_TRUE(back.valid()) << path;
        const TexturePalette* after =
            back->getStateSet() ? PaletteMapping::paletteOf(*back->getStateSet()) : nullptr;
        ASSERT_TRUE(after) << ext;
        const osg::Image& x = *before->getPaletteImage();
        const osg::Image& y = *after->getPaletteImage();
        ASSERT_EQ(x.getTotalSizeInBytes(), y.getTotalSizeInBytes());
        EXPECT_TRUE(std::equal(x.data(), x.data() + x.getTotalSizeInBytes(), y.data())) << ext;
    }
}
