// Streets as on a map (paper 004 §3.2.3; osgLoA::StreetPresentation): road classes from sub-types
// and widths, the casing coverage, and the street map (edge distances, texel counts, widths)
// against values computed by hand for quads of known size.
#include "support/TestSupport.h"
#include "support/TopDownView.h"

#include <osgLoA/city/CityGenerator>
#include <osgLoA/semantics/Feature>
#include <osgLoA/semantics/FeatureIndex>
#include <osgLoA/semantics/FeatureSubType>
#include <osgLoA/styles/GraphicStyleCatalog>
#include <osgLoA/styles/SignedDistanceFont>
#include <osgLoA/styles/StreetLabels>
#include <osgLoA/styles/StreetPresentation>

#include <osg/Group>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <osgDB/FileUtils>
#include <osgDB/ReadFile>
#include <set>

using namespace osgLoA;
using SP = StreetPresentation;

namespace
{
osg::ref_ptr<osg::Node> road(unsigned id, const std::string& subType, double x0, double y0, double x1,
                             double y1)
{
    return loatest::featureQuad(id, FeatureType::Street, subType, x0, y0, x1, y1);
}
} // namespace

TEST(StreetPresentationTest, RoadClasses)
{
    EXPECT_EQ(SP::classOf("major", 0.0), SP::MAJOR);
    EXPECT_EQ(SP::classOf("Primary", 0.0), SP::MAJOR);
    EXPECT_EQ(SP::classOf("residential", 20.0), SP::MINOR); // the model's word wins over the width
    EXPECT_EQ(SP::classOf("footway", 0.0), SP::PATH);
    EXPECT_EQ(SP::classOf("railway", 0.0), SP::RAIL);
    // CityGML/CityJSON "road" and unnamed streets: by width (7.5 and 3.5 m).
    EXPECT_EQ(SP::classOf("road", 12.0), SP::MAJOR);
    EXPECT_EQ(SP::classOf("road", 7.5), SP::MAJOR);
    EXPECT_EQ(SP::classOf("road", 7.0), SP::MINOR);
    EXPECT_EQ(SP::classOf("", 6.0), SP::MINOR);
    EXPECT_EQ(SP::classOf("", 3.0), SP::PATH);
    EXPECT_EQ(SP::classOf("road", 0.0), SP::UNKNOWN);
    // The shader's class codes are FeatureSubType's.
    EXPECT_EQ(FeatureSubType::code("major"), 32);
    EXPECT_EQ(FeatureSubType::code("minor"), 33);
    EXPECT_EQ(FeatureSubType::code("path"), 34);
    EXPECT_EQ(FeatureSubType::code("rail"), 35);
    EXPECT_EQ(FeatureSubType::code("railway"), 36);
    EXPECT_EQ(FeatureSubType::code("track"), 37);
    // Casing: 1 px on pixels of 0.1 m: full at the edge, half at 0.15 m... (1 + 1/2 - d / 0.1).
    EXPECT_DOUBLE_EQ(SP::casingCoverage(0.0, 0.1, 1.0), 1.0);
    EXPECT_NEAR(SP::casingCoverage(0.1, 0.1, 1.0), 0.5, 1e-12);
    EXPECT_DOUBLE_EQ(SP::casingCoverage(0.2, 0.1, 1.0), 0.0);
    EXPECT_NEAR(SP::casingCoverage(0.2, 0.1, 2.0), 0.5, 1e-12);
    EXPECT_DOUBLE_EQ(SP::casingCoverage(0.0, 0.1, 0.0), 0.0);   // paths: no casing
    EXPECT_DOUBLE_EQ(SP::casingCoverage(-0.05, 0.1, 1.0), 1.0); // on the edge, within interpolation
    // The style maps sub-type codes to classes as classOf does (the shader's only source).
    osg::ref_ptr<GraphicStyle> style = GraphicStyleCatalog::instance().create("streets");
    const osg::Uniform* classes = style->getParameter("loa_streets_classOf");
    ASSERT_NE(classes, nullptr);
    int k = 0;
    for (const char* word :
         {"major", "minor", "path", "rail", "railway", "track", "residential", "river", ""})
    {
        classes->getElement(unsigned(FeatureSubType::code(word)), k);
        EXPECT_EQ(k, int(SP::classOf(word, 0.0))) << word;
    }
    EXPECT_NE(GraphicStyleCatalog::instance().create("streets"), nullptr);
}

TEST(StreetPresentationTest, StreetMapDistancesAndWidths)
{
    // A 100 x 10 m street, a 60 x 4 m one beside it, and an L of two 6 m streets meeting.
    osg::ref_ptr<osg::Group> root = new osg::Group;
    root->addChild(road(1, "road", 0, 0, 100, 10).get());
    root->addChild(road(2, "", 0, 20, 60, 24).get());
    root->addChild(road(3, "", 0, 40, 50, 46).get());
    root->addChild(road(4, "", 44, 46, 50, 90).get());
    const SP::StreetMap map = SP::computeStreetMap(*root);
    ASSERT_TRUE(map.valid());
    EXPECT_EQ(map.streetFeatures, 4u);
    EXPECT_EQ(map.triangles, 8u);
    // Texels of 0.1 m (100 / 2046 is finer than the minimum); texel centres inside the streets
    // (closed): 1000 x 100 + 600 x 40 + 500 x 60 + 60 x 440 (the L's two arms; they meet at
    // y = 46, shared by neither's centres).
    EXPECT_DOUBLE_EQ(map.grid.texelSize, 0.1);
    EXPECT_EQ(map.streetTexels, std::size_t(100000 + 24000 + 30000 + 26400));
    // The signed distance to the nearest edge: 5 m on the wide street's centre line, 2 m on the
    // narrow one's, -5 m half-way between them, 0 on an edge (within a texel).
    EXPECT_NEAR(map.sample(50.0, 5.0), 5.0, 0.1);
    EXPECT_NEAR(map.sample(30.0, 22.0), 2.0, 0.1);
    EXPECT_NEAR(map.sample(50.0, 15.0), -5.0, 0.1);
    EXPECT_NEAR(map.sample(50.0, 10.0), 0.0, 0.02);
    EXPECT_NEAR(map.sample(0.0, 5.0), 0.0, 0.02);
    // The L's joint is one surface: at the seam (47, 46) the nearest edge is 3 m away, not 0.
    EXPECT_NEAR(map.sample(47.0, 46.0), 3.0, 0.15);
    // Widths: 2 p90 / 0.9 of each street's distances.
    ASSERT_EQ(map.widths.size(), 4u);
    EXPECT_NEAR(map.widths[0].second, 10.0, 0.3);
    EXPECT_NEAR(map.widths[1].second, 4.0, 0.3);
    EXPECT_NEAR(map.widths[3].second, 6.0, 0.4);
    EXPECT_EQ(SP::classOf("road", map.widths[0].second), SP::MAJOR);
    EXPECT_EQ(SP::classOf("", map.widths[1].second), SP::MINOR);
    // No street: no map; impossible parameters: an error naming them.
    osg::ref_ptr<osg::Group> bare = new osg::Group;
    bare->addChild(loatest::asFeature(loatest::planeQuad(0, 0, 1, 1).get(), 9, FeatureType::Terrain).get());
    EXPECT_FALSE(SP::computeStreetMap(*bare).valid());
    EXPECT_THROW(SP::computeStreetMap(*root, 2), std::invalid_argument);
    EXPECT_THROW(SP::computeStreetMap(*root, 64, std::nan("")), std::invalid_argument);
}

// --- street labels (osgLoA::StreetLabels, SignedDistanceFont) ---------------------------------------
// Street labels (osgLoA::StreetLabels, SignedDistanceFont): Green's signed distance fields
// against brute force and a hand-computed square; the layout by hand (a label centred on its
// street, glyphs along the line at their advances, never upside down, vertical labels reading
// upwards, too-short streets unlabelled, a corner avoided, collisions and repeats avoided, the size
// from the street's width in pixels, opacity); the labelled streets of the demo city and of West
// Oakland (OpenStreetMap) against counts made by hand; the Feature label round trip.

namespace
{
const double kPiTest = 3.14159265358979323846;

/** The font the labels use (fonts-dejavu-core, installed by scripts/setup). */
SignedDistanceFont& font()
{
    static osg::ref_ptr<SignedDistanceFont> f;
    if (!f)
    {
        const std::string file = SignedDistanceFont::defaultFontFile();
        if (file.empty()) throw std::runtime_error("no DejaVu font: install fonts-dejavu-core");
        f = new SignedDistanceFont(file);
        std::vector<unsigned> codes;
        for (unsigned c = 32; c < 127; ++c)
            codes.push_back(c);
        f->require(codes);
    }
    return *f;
}

StreetLabels::Street street(const std::string& name, std::vector<osg::Vec3d> points, int roadClass = 0,
                            double width = 0.0)
{
    StreetLabels::Street s;
    s.label = name;
    s.text = SignedDistanceFont::decodeUtf8(name);
    s.points = std::move(points);
    s.roadClass = roadClass;
    s.width = width;
    return s;
}

/** An orthographic top-down view: window pixel = world unit * scale, over [0, w] x [0, h]. */
StreetLabels::View topView(double w, double h, double scale = 1.0)
{
    StreetLabels::View v;
    v.width = w;
    v.height = h;
    v.sceneToClip = osg::Matrixd::ortho(0.0, w / scale, 0.0, h / scale, -100.0, 100.0);
    return v;
}

/** The text's width in em, as the layout measures it (advances and kerning). */
double textEm(const std::string& text)
{
    const std::vector<unsigned> codes = SignedDistanceFont::decodeUtf8(text);
    double em = 0.0;
    for (std::size_t i = 0; i < codes.size(); ++i)
    {
        if (i > 0) em += font().kerning(codes[i - 1], codes[i]);
        em += font().glyph(codes[i])->advance;
    }
    return em;
}
} // namespace

TEST(SignedDistanceFontTest, GreensFieldOfASquareByHand)
{
    // A 9 x 9 mask, all inside; downsample 3, spread 2: the field is 3 + 4 texels a side.
    std::vector<unsigned char> mask(81, 1);
    int fw = 0, fh = 0;
    const std::vector<float> d = SignedDistanceFont::signedDistance(mask, 9, 9, 3, 2, fw, fh);
    ASSERT_EQ(fw, 7);
    ASSERT_EQ(fh, 7);
    // Field texel (2, 2) is centred on mask texel (1, 1): the nearest outside centre is 2 texels
    // away (x = -1), the edge 1.5: 0.5 field texels.
    EXPECT_NEAR(d[2 * 7 + 2], 0.5f, 1e-6);
    // The centre (3, 3) on mask texel (4, 4): 5 texels to the outside, 4.5 to the edge: 1.5.
    EXPECT_NEAR(d[3 * 7 + 3], 1.5f, 1e-6);
    // Texel (0, 0) on mask (-5, -5): sqrt(50) to the corner texel's centre, less 0.5, over 3.
    EXPECT_NEAR(d[0], -(std::sqrt(50.0f) - 0.5f) / 3.0f, 1e-5);
    // A mask with nothing inside: -(spread + 1) everywhere.
    std::vector<unsigned char> empty(81, 0);
    const std::vector<float> e = SignedDistanceFont::signedDistance(empty, 9, 9, 3, 2, fw, fh);
    for (float v : e)
        EXPECT_EQ(v, -3.0f);
    EXPECT_THROW(SignedDistanceFont::signedDistance(mask, 9, 8, 3, 2, fw, fh), std::invalid_argument);
}

TEST(SignedDistanceFontTest, GlyphFieldsAgreeWithBruteForce)
{
    // An irregular mask (a ring with a notch and a stray texel) against the definition: for each
    // field texel, the distance to the nearest texel centre of the other kind, less half a texel.
    const int w = 23, h = 17, ds = 3, spread = 3;
    std::vector<unsigned char> mask(std::size_t(w * h), 0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
        {
            const double r = std::hypot(x - 11.0, y - 8.0);
            mask[std::size_t(y * w + x)] = (r > 3.0 && r < 7.5 && !(x > 11 && std::abs(y - 8) < 2)) ? 1 : 0;
        }
    mask[std::size_t(1 * w + 20)] = 1;
    int fw = 0, fh = 0;
    const std::vector<float> d = SignedDistanceFont::signedDistance(mask, w, h, ds, spread, fw, fh);
    const int margin = spread * ds;
    double worst = 0.0;
    for (int j = 0; j < fh; ++j)
        for (int i = 0; i < fw; ++i)
        {
            const int px = i * ds + ds / 2 - margin, py = j * ds + ds / 2 - margin;
            auto inside = [&](int x, int y)
            { return x >= 0 && y >= 0 && x < w && y < h && mask[std::size_t(y * w + x)] != 0; };
            const bool in = inside(px, py);
            double best = std::numeric_limits<double>::infinity();
            for (int y = -margin - ds; y < h + margin + ds; ++y)
                for (int x = -margin - ds; x < w + margin + ds; ++x)
                    if (inside(x, y) != in) best = std::min(best, std::hypot(double(x - px), double(y - py)));
            const double expected = (in ? best - 0.5 : -(best - 0.5)) / ds;
            worst = std::max(worst, std::fabs(expected - d[std::size_t(j * fw + i)]));
        }
    EXPECT_LT(worst, 1e-5);
}

TEST(SignedDistanceFontTest, AtlasHoldsTheGlyphsOfTheFont)
{
    SignedDistanceFont& f = font();
    // DejaVu Sans Bold: capitals 0.729 em high (1493 of 2048 units).
    EXPECT_NEAR(f.capHeight(), 0.729, 0.02);
    const SignedDistanceFont::Glyph* space = f.glyph(' ');
    ASSERT_NE(space, nullptr);
    EXPECT_TRUE(space->blank);
    EXPECT_GT(space->advance, 0.2f);
    // 'I' is a bar: its atlas centre is inside (> 0.5), the corners of its field outside.
    const SignedDistanceFont::Glyph* bar = f.glyph('I');
    ASSERT_NE(bar, nullptr);
    ASSERT_FALSE(bar->blank);
    const osg::Image& atlas = *f.getAtlas();
    auto value = [&](const osg::Vec2f& t)
    {
        const int x = std::min(atlas.s() - 1, int(t.x() * atlas.s())),
                  y = std::min(atlas.t() - 1, int(t.y() * atlas.t()));
        return int(*atlas.data(x, y));
    };
    EXPECT_GT(value((bar->texMin + bar->texMax) * 0.5f), 128 + 40);
    EXPECT_LT(value(bar->texMin + osg::Vec2f(0.5f / atlas.s(), 0.5f / atlas.t())), 10);
    // The quad covers the glyph's outline plus the spread: wider than the bar, as high as a capital
    // plus two margins.
    const float margin = float(f.getParameters().spread) / f.texelsPerEm();
    EXPECT_NEAR(bar->quadMax.y() - bar->quadMin.y(), f.capHeight() + 2.0f * margin, 0.05f);
    EXPECT_EQ(SignedDistanceFont::decodeUtf8("Stra\xc3\x9f"
                                             "e"),
              (std::vector<unsigned>{'S', 't', 'r', 'a', 0xDF, 'e'}));
    EXPECT_THROW(osg::ref_ptr<SignedDistanceFont>(new SignedDistanceFont("/nonexistent/font.ttf")),
                 std::runtime_error);
}

TEST(StreetLabelsTest, LabelCentredOnAStraightStreetWithGlyphsAtTheirAdvances)
{
    StreetLabels::Parameters p;
    const std::vector<StreetLabels::Street> streets = {street("Oak Street", {{100, 200, 0}, {500, 200, 0}})};
    StreetLabels::Statistics st;
    const auto labels = StreetLabels::layout(streets, topView(640, 400), font(), p, {}, &st);
    ASSERT_EQ(labels.size(), 1u);
    const StreetLabels::Label& l = labels[0];
    EXPECT_EQ(st.labels, 1u);
    EXPECT_FALSE(l.reversed);
    // No width given: the major class's size; centred at the street's middle.
    EXPECT_DOUBLE_EQ(l.size, 12.0);
    EXPECT_NEAR(l.anchor.x(), 300.0, 1e-9);
    EXPECT_NEAR(l.anchor.y(), 200.0, 1e-9);
    // 9 drawn glyphs (the space has none); the first starts half the text's width before the middle.
    ASSERT_EQ(l.glyphs.size(), 9u);
    const double L = 12.0 * textEm("Oak Street");
    const SignedDistanceFont::Glyph* O = font().glyph('O');
    EXPECT_NEAR(l.glyphs[0].centre.x(), 300.0 - 0.5 * L + 0.5 * 12.0 * O->advance, 1e-6);
    for (std::size_t i = 0; i < l.glyphs.size(); ++i)
    {
        EXPECT_NEAR(l.glyphs[i].angle, 0.0, 1e-9);
        EXPECT_NEAR(l.glyphs[i].centre.y(), 200.0, 1e-9);
        if (i > 0)
        {
            EXPECT_GT(l.glyphs[i].centre.x(), l.glyphs[i - 1].centre.x());
        }
    }
    // 'k' follows 'a' by half of each one's advance (plus kerning).
    const double ak = 12.0 * (0.5 * font().glyph('a')->advance + font().kerning('a', 'k') +
                              0.5 * font().glyph('k')->advance);
    EXPECT_NEAR(l.glyphs[2].centre.x() - l.glyphs[1].centre.x(), ak, 1e-6);
    // The window depth of an orthographic view of z = 0 between -100 and 100: 0.5.
    EXPECT_NEAR(l.glyphs[0].depth, 0.5, 1e-9);
}

TEST(StreetLabelsTest, NeverUpsideDownAndVerticalLabelsReadUpwards)
{
    StreetLabels::Parameters p;
    // Drawn from east to west: the text still runs left to right, against the line.
    auto labels = StreetLabels::layout({street("Elm Street", {{500, 200, 0}, {100, 200, 0}})},
                                       topView(640, 400), font(), p);
    ASSERT_EQ(labels.size(), 1u);
    EXPECT_TRUE(labels[0].reversed);
    EXPECT_LT(labels[0].glyphs.front().centre.x(), labels[0].glyphs.back().centre.x());
    for (const auto& g : labels[0].glyphs)
        EXPECT_NEAR(g.angle, 0.0, 1e-9);
    // North-south in either direction: rotated by +90 degrees, first glyph lowest.
    for (bool southward : {false, true})
    {
        std::vector<osg::Vec3d> pts = {{300, 50, 0}, {300, 350, 0}};
        if (southward) std::swap(pts[0], pts[1]);
        labels = StreetLabels::layout({street("3rd Avenue", pts)}, topView(640, 400), font(), p);
        ASSERT_EQ(labels.size(), 1u);
        EXPECT_EQ(labels[0].reversed, southward);
        EXPECT_LT(labels[0].glyphs.front().centre.y(), labels[0].glyphs.back().centre.y());
        for (const auto& g : labels[0].glyphs)
            EXPECT_NEAR(g.angle, 0.5 * kPiTest, 1e-9);
    }
    // A diagonal from upper right to lower left reads from lower left, at +45 degrees... turned:
    labels = StreetLabels::layout({street("Pine Street", {{500, 350, 0}, {100, -50 + 0, 0}})},
                                  topView(640, 400), font(), p);
    ASSERT_EQ(labels.size(), 1u);
    for (const auto& g : labels[0].glyphs)
        EXPECT_NEAR(g.angle, 0.25 * kPiTest, 1e-9);
}

TEST(StreetLabelsTest, InPerspectiveTheAnchorIsThePerspectiveCorrectPointOfTheStreet)
{
    // A street running away from a camera 2 m above it, from 5 m to 400 m ahead and crossing the
    // near plane behind: the label's scene anchor projects onto its window anchor (the scene point
    // is interpolated perspective-correctly between the projected vertices), and every glyph's
    // depth is the projection's depth of the street there (it grows along the street).
    StreetLabels::Parameters p;
    StreetLabels::View v;
    v.width = 1920;
    v.height = 1080;
    const osg::Matrixd mv =
        osg::Matrixd::lookAt(osg::Vec3d(0, 0, 2), osg::Vec3d(0, 1, 2), osg::Vec3d(0, 0, 1));
    v.sceneToClip = mv * osg::Matrixd::perspective(60.0, 1920.0 / 1080.0, 0.5, 1000.0);
    // Slanted so that its window line is long enough for a label.
    const auto labels =
        StreetLabels::layout({street("Oak Street", {{-3, -20, 0}, {2, 5, 0}, {60, 400, 0}})}, v, font(), p);
    ASSERT_GE(labels.size(), 1u);
    for (const auto& l : labels)
    {
        const osg::Vec4d c = osg::Vec4d(l.sceneAnchor, 1.0) * v.sceneToClip;
        const osg::Vec2d w((c.x() / c.w() * 0.5 + 0.5) * v.width, (c.y() / c.w() * 0.5 + 0.5) * v.height);
        EXPECT_LT((w - l.anchor).length(), 1e-6);
        EXPECT_NEAR(l.sceneAnchor.z(), 0.0, 1e-9);
        for (const auto& g : l.glyphs)
        {
            EXPECT_GT(g.depth, 0.0);
            EXPECT_LT(g.depth, 1.0);
        }
    }
}

TEST(StreetLabelsTest, AFontWithoutACharacterGivesABlankNotABox)
{
    // U+10FFFC is in no font (a private-use plane): FreeType gives the .notdef box, counted missing.
    osg::ref_ptr<SignedDistanceFont> f = new SignedDistanceFont(SignedDistanceFont::defaultFontFile());
    f->require({'A', 0x10FFFCu});
    EXPECT_EQ(f->getMissing(), 1u);
    ASSERT_NE(f->glyph(0x10FFFCu), nullptr);
    EXPECT_TRUE(f->glyph(0x10FFFCu)->blank);
    EXPECT_FALSE(f->glyph('A')->blank);
}

TEST(StreetLabelsTest, ShortStreetsCornersAndTheViewportLeaveLabelsOut)
{
    StreetLabels::Parameters p;
    // 12 px x the text's width is about 80 px for "Oak Street": a 60 px street has no room.
    StreetLabels::Statistics st;
    auto labels = StreetLabels::layout({street("Oak Street", {{100, 200, 0}, {160, 200, 0}})},
                                       topView(640, 400), font(), p, {}, &st);
    EXPECT_TRUE(labels.empty());
    EXPECT_EQ(st.streets, 0u);
    // An L whose corner lies at the middle: the label goes on one leg, straight.
    labels = StreetLabels::layout({street("Oak Street", {{100, 200, 0}, {300, 200, 0}, {300, 400, 0}})},
                                  topView(640, 480), font(), p);
    ASSERT_EQ(labels.size(), 1u);
    for (const auto& g : labels[0].glyphs)
        EXPECT_NEAR(g.angle, labels[0].glyphs[0].angle, 1e-9);
    // A street running off the window: the label stays inside it.
    labels = StreetLabels::layout({street("Oak Street", {{-400, 200, 0}, {120, 200, 0}})}, topView(640, 400),
                                  font(), p);
    ASSERT_EQ(labels.size(), 1u);
    osg::Vec2d q[4];
    for (const auto& g : labels[0].glyphs)
    {
        StreetLabels::glyphQuad(g, labels[0].size, font(), q);
        for (const osg::Vec2d& c : q)
            EXPECT_GE(c.x(), 0.0);
    }
    // Behind the camera (perspective, the street behind the eye): no run, no label.
    StreetLabels::View persp;
    persp.width = 640;
    persp.height = 400;
    persp.sceneToClip = osg::Matrixd::lookAt(osg::Vec3d(0, 0, 2), osg::Vec3d(0, 1, 2), osg::Vec3d(0, 0, 1)) *
                        osg::Matrixd::perspective(60.0, 1.6, 1.0, 1000.0);
    labels = StreetLabels::layout({street("Oak Street", {{-200, -10, 0}, {200, -10, 0}})}, persp, font(), p);
    EXPECT_TRUE(labels.empty());
}

TEST(StreetLabelsTest, CrossingStreetsAndRepeatedNamesDoNotCollide)
{
    StreetLabels::Parameters p;
    // Two streets crossing at their middles: the major one keeps the middle, the minor one moves
    // off the crossing; no glyph boxes overlap.
    const std::vector<StreetLabels::Street> streets = {
        street("Minor Road", {{320, 60, 0}, {320, 340, 0}}, 1),
        street("Major Road", {{120, 200, 0}, {520, 200, 0}}, 0)};
    StreetLabels::Statistics st;
    const auto labels = StreetLabels::layout(streets, topView(640, 400), font(), p, {}, &st);
    ASSERT_EQ(labels.size(), 2u);
    EXPECT_EQ(labels[0].street, 1u); // major first
    EXPECT_NEAR(labels[0].anchor.x(), 320.0, 1e-9);
    EXPECT_GE(st.collisions, 1u);
    EXPECT_GT(std::fabs(labels[1].anchor.y() - 200.0), 0.5 * 10.8 * textEm("Minor Road") - 1e-6);
    for (const auto& a : labels[0].glyphs)
        for (const auto& b : labels[1].glyphs)
        {
            osg::Vec2d qa[4], qb[4];
            StreetLabels::glyphBox(a, labels[0].size, font(), 0.0, qa);
            StreetLabels::glyphBox(b, labels[1].size, font(), 0.0, qb);
            double ax0 = 1e9, ax1 = -1e9, ay0 = 1e9, ay1 = -1e9, bx0 = 1e9, bx1 = -1e9, by0 = 1e9, by1 = -1e9;
            for (int i = 0; i < 4; ++i)
            {
                ax0 = std::min(ax0, qa[i].x()), ax1 = std::max(ax1, qa[i].x());
                ay0 = std::min(ay0, qa[i].y()), ay1 = std::max(ay1, qa[i].y());
                bx0 = std::min(bx0, qb[i].x()), bx1 = std::max(bx1, qb[i].x());
                by0 = std::min(by0, qb[i].y()), by1 = std::max(by1, qb[i].y());
            }
            EXPECT_TRUE(ax1 <= bx0 || bx1 <= ax0 || ay1 <= by0 || by1 <= ay0);
        }
    // The same name on two ways end to end (as OSM splits streets): the second label only
    // repeatPixels (300) from the first.
    const std::vector<StreetLabels::Street> ways = {street("Adeline Street", {{0, 200, 0}, {330, 200, 0}}),
                                                    street("Adeline Street", {{330, 200, 0}, {660, 200, 0}})};
    auto twice = StreetLabels::layout(ways, topView(700, 400), font(), p);
    ASSERT_EQ(twice.size(), 2u);
    EXPECT_GE((twice[0].anchor - twice[1].anchor).length(), 300.0);
    p.repeatPixels = 500.0f; // the second way's anchors lie at most 455 px from the first's
    EXPECT_EQ(StreetLabels::layout(ways, topView(700, 400), font(), p).size(), 1u);
}

TEST(StreetLabelsTest, SizeFollowsTheStreetsWidthOnScreenAndOpacityTheMap)
{
    StreetLabels::Parameters p;
    // A major street 10 m wide seen at 1 px/m: 0.8 x 10 = 8 px, raised to the 10 px minimum; at
    // 1.4 px/m: 11.2 px; at 3 px/m: 24 px, lowered to the class's 12 px. A minor one: 10.8 px at most.
    const auto at = [&](double scale, int cls)
    {
        const auto l = StreetLabels::layout({street("Oak Street", {{10, 50, 0}, {210, 50, 0}}, cls, 10.0)},
                                            topView(640, 400, scale), font(), p);
        return l.empty() ? 0.0 : l[0].size;
    };
    EXPECT_NEAR(at(1.0, 0), 10.0, 1e-5);
    EXPECT_NEAR(at(1.4, 0), 11.2, 1e-5);
    EXPECT_NEAR(at(3.0, 0), 12.0, 1e-5);
    EXPECT_NEAR(at(3.0, 1), 10.8, 1e-5);
    // Opacity: the function's value at the anchor; below minOpacity no label.
    const std::vector<StreetLabels::Street> s = {street("Oak Street", {{100, 200, 0}, {500, 200, 0}})};
    auto labels =
        StreetLabels::layout(s, topView(640, 400), font(), p,
                             [](std::size_t, const osg::Vec3d& q) { return float(q.x() / 1000.0); });
    ASSERT_EQ(labels.size(), 1u);
    EXPECT_NEAR(labels[0].opacity, 0.3f, 1e-6);
    EXPECT_NEAR(labels[0].sceneAnchor.x(), 300.0, 1e-6);
    labels = StreetLabels::layout(s, topView(640, 400), font(), p,
                                  [](std::size_t, const osg::Vec3d&) { return 0.01f; });
    EXPECT_TRUE(labels.empty());
    // A style without labels, the streets style with them.
    StreetLabels::Parameters q;
    EXPECT_FALSE(StreetLabels::parametersOf(*GraphicStyleCatalog::instance().create("cartographic"), q));
    ASSERT_TRUE(StreetLabels::parametersOf(*GraphicStyleCatalog::instance().create("streets"), q));
    EXPECT_EQ(q.size, 12.0f);
}

TEST(StreetLabelsTest, DemoCityStreetsByHand)
{
    // The demo city of 4 x 4 blocks: 5 road lines each way, each a labelled street feature;
    // centre lines on the road surface (its height under them).
    CityParameters cp;
    cp.blocksX = 4;
    cp.blocksY = 4;
    CityGenerator generator(cp);
    osg::ref_ptr<osg::Node> city = generator.generate();
    EXPECT_EQ(generator.getLayout().roadLinesX.size() + generator.getLayout().roadLinesY.size(), 10u);
    FeatureIndex index(*city);
    const std::vector<StreetLabels::Street> streets = StreetLabels::collect(index);
    EXPECT_EQ(streets.size(), 10u);
    std::set<std::string> names;
    for (const auto& s : streets)
    {
        names.insert(s.label);
        EXPECT_GE(s.points.size(), 2u);
        // Widths: the generator's 18 m major and 10 m minor roads (area / length).
        EXPECT_TRUE(std::fabs(s.width - cp.majorRoadWidth) < 0.05 ||
                    std::fabs(s.width - cp.minorRoadWidth) < 0.05)
            << s.label << " " << s.width;
    }
    EXPECT_EQ(names.size(), 10u);
    EXPECT_TRUE(names.count("Oak Boulevard") || names.count("Oak Street"));
    EXPECT_TRUE(names.count("1st Parkway") || names.count("1st Avenue"));
}

TEST(StreetLabelsTest, WestOaklandStreetsCountedByHand)
{
    const std::string file = std::string(LOA_SOURCE_DIR) + "/data/cache/python-osmnx-doc/West-Oakland.osm";
    if (!osgDB::fileExists(file)) GTEST_SKIP() << file << " is absent: run scripts/fetch-test-data";
    osg::ref_ptr<osg::Node> model = osgDB::readRefNodeFile(file);
    ASSERT_TRUE(model.valid());
    FeatureIndex index(*model);
    const std::vector<StreetLabels::Street> streets = StreetLabels::collect(index);
    // Counted by hand from the file (a script over its XML): 31 ways with a highway tag the importer
    // draws (highwayWidth > 0, area != yes, 2+ nodes present), 20 of them with a name or ref, 9
    // distinct names.
    unsigned features = 0;
    for (const auto& e : index.entries())
        features += e.feature->getType() == FeatureType::Street && !e.feature->getCentreline().empty();
    EXPECT_EQ(features, 31u);
    EXPECT_EQ(streets.size(), 20u);
    std::set<std::string> names;
    for (const auto& s : streets)
        names.insert(s.label);
    EXPECT_EQ(names.size(), 9u);
    // Flat OSM streets: every centre-line vertex on the surface (z of the ribbon, 0 here).
    for (const auto& s : streets)
        for (const auto& pt : s.points)
            EXPECT_LT(std::fabs(pt.z()), 1.0) << s.label;
}
