// Texture-object histogram (paper 003): triangle areas, proportions, CPU texel weights and the
// weighted colour table, on hand-built meshes with hand-computed values.
#include <osgLoA/palette/TextureHistogram>

#include <osg/Geode>
#include <osg/Group>
#include <osg/Texture2D>

#include <gtest/gtest.h>

#include <numeric>

using namespace osgLoA;
using TH = TextureHistogram;

namespace
{
/** A geometry of separate triangles (GL_TRIANGLES, DrawArrays) from object and uv corners. */
osg::ref_ptr<osg::Geometry> triangles(const std::vector<osg::Vec3>& p, const std::vector<osg::Vec2>& uv)
{
    osg::ref_ptr<osg::Geometry> g = new osg::Geometry;
    g->setVertexArray(new osg::Vec3Array(p.begin(), p.end()));
    g->setTexCoordArray(0, new osg::Vec2Array(uv.begin(), uv.end()), osg::Array::BIND_PER_VERTEX);
    g->addPrimitiveSet(new osg::DrawArrays(GL_TRIANGLES, 0, GLsizei(p.size())));
    return g;
}

/** A 2 x 2 square in object space, uv corners (u0, v0)-(u1, v1), as two indexed triangles
 *  (0, 1, 2) and (0, 2, 3): lower-right and upper-left of the diagonal. */
osg::ref_ptr<osg::Geometry> quad(float u0, float v0, float u1, float v1)
{
    osg::ref_ptr<osg::Geometry> g = new osg::Geometry;
    osg::ref_ptr<osg::Vec3Array> p = new osg::Vec3Array;
    p->push_back(osg::Vec3(0, 0, 0));
    p->push_back(osg::Vec3(2, 0, 0));
    p->push_back(osg::Vec3(2, 2, 0));
    p->push_back(osg::Vec3(0, 2, 0));
    osg::ref_ptr<osg::Vec2Array> t = new osg::Vec2Array;
    t->push_back(osg::Vec2(u0, v0));
    t->push_back(osg::Vec2(u1, v0));
    t->push_back(osg::Vec2(u1, v1));
    t->push_back(osg::Vec2(u0, v1));
    g->setVertexArray(p.get());
    g->setTexCoordArray(0, t.get(), osg::Array::BIND_PER_VERTEX);
    osg::ref_ptr<osg::DrawElementsUShort> e = new osg::DrawElementsUShort(GL_TRIANGLES);
    for (unsigned short i : {0, 1, 2, 0, 2, 3})
        e->push_back(i);
    g->addPrimitiveSet(e.get());
    return g;
}

const ImageBorder kRepeat(WrapMode::Repeat, WrapMode::Repeat);
const ImageBorder kClamp(WrapMode::Clamp, WrapMode::Clamp);
const ImageBorder kMirror(WrapMode::Mirror, WrapMode::Mirror);

double at(const std::vector<double>& w, int x, int y, int width = 4)
{
    return w[std::size_t(y * width + x)];
}
} // namespace

TEST(TextureHistogramTest, QuadAreasProportionsAndUniformWeights)
{
    osg::ref_ptr<osg::Geometry> g = quad(0, 0, 1, 1);
    const auto tris = TH::triangleAreas(*g);
    ASSERT_EQ(tris.size(), 2u);
    for (const auto& t : tris)
    {
        EXPECT_DOUBLE_EQ(t.objectArea, 2.0);  // half of the 2 x 2 square
        EXPECT_DOUBLE_EQ(t.textureArea, 0.5); // half of the unit uv square (uv units)
        EXPECT_DOUBLE_EQ(t.objectProportion, 0.5);
        EXPECT_DOUBLE_EQ(t.textureProportion, 0.5);
    }
    EXPECT_EQ(tris[1].uv[2], osg::Vec2d(0, 1));
    // Texel centres ((i + .5) / 4, (j + .5) / 4) never lie on the square's sides; the four on
    // the diagonal go to exactly one triangle (the shared edge is a left edge of one and a right
    // edge of the other), so every texel is covered once: 0.5 * 0.5.
    for (const ImageBorder& b : {kRepeat, kClamp, kMirror})
    {
        const auto w = TH::texelWeights(*g, 4, 4, b);
        ASSERT_EQ(w.size(), 16u);
        for (double v : w)
            EXPECT_DOUBLE_EQ(v, 0.25);
    }
    // The same square as GL_QUADS and as a triangle strip: same triangles, same weights.
    osg::ref_ptr<osg::Geometry> q = new osg::Geometry(*g, osg::CopyOp::SHALLOW_COPY);
    q->removePrimitiveSet(0);
    q->addPrimitiveSet(new osg::DrawArrays(GL_QUADS, 0, 4));
    EXPECT_EQ(TH::texelWeights(*q, 4, 4, kClamp), std::vector<double>(16, 0.25));
    osg::ref_ptr<osg::Geometry> s = new osg::Geometry(*g, osg::CopyOp::SHALLOW_COPY);
    s->removePrimitiveSet(0);
    osg::ref_ptr<osg::DrawElementsUByte> strip = new osg::DrawElementsUByte(GL_TRIANGLE_STRIP);
    for (unsigned char i : {0, 1, 3, 2})
        strip->push_back(i);
    s->addPrimitiveSet(strip.get());
    EXPECT_EQ(TH::triangleAreas(*s).size(), 2u);
    EXPECT_EQ(TH::texelWeights(*s, 4, 4, kClamp), std::vector<double>(16, 0.25));
}

TEST(TextureHistogramTest, RightTrianglesSplitTheDiagonalByTheFillRule)
{
    // Lower-left half: centres with i + j <= 2 strictly inside (6); the 4 with i + j = 3 lie on
    // the hypotenuse, a right edge of this counter-clockwise triangle, so they are excluded.
    osg::ref_ptr<osg::Geometry> lower =
        triangles({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 0}, {1, 0}, {0, 1}});
    const auto tl = TH::triangleAreas(*lower);
    ASSERT_EQ(tl.size(), 1u);
    EXPECT_DOUBLE_EQ(tl[0].objectArea, 0.5);
    EXPECT_DOUBLE_EQ(tl[0].textureArea, 0.5);
    EXPECT_DOUBLE_EQ(tl[0].objectProportion, 1.0);
    EXPECT_DOUBLE_EQ(tl[0].textureProportion, 1.0);
    const auto wl = TH::texelWeights(*lower, 4, 4, kClamp);
    // The complementary upper-right half has the hypotenuse as a left edge: 10 texels.
    osg::ref_ptr<osg::Geometry> upper =
        triangles({{1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{1, 0}, {1, 1}, {0, 1}});
    const auto wu = TH::texelWeights(*upper, 4, 4, kClamp);
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i)
        {
            EXPECT_DOUBLE_EQ(at(wl, i, j), i + j <= 2 ? 1.0 : 0.0) << i << "," << j;
            EXPECT_DOUBLE_EQ(at(wu, i, j), i + j >= 3 ? 1.0 : 0.0) << i << "," << j;
        }
    // Horizontal edges through texel centres (row 0 at v = 0.125, row 3 at v = 0.875): a bottom
    // edge is included, a top edge is not. Triangle (0, .125) (1, .125) (.5, 1): row 0 covered
    // for 0 < u < 1 (4 texels); row 3 (v = .875): |u - .5| < .5 * (1 - .875) / .875 = 0.0714:
    // no centre. Rows 1 and 2: |u - .5| < .5 * (1 - v) / .875: v = .375 -> .357 (u = .375,
    // .625), v = .625 -> .214 (u = .375, .625).
    osg::ref_ptr<osg::Geometry> bottomEdge =
        triangles({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 0.125f}, {1, 0.125f}, {0.5f, 1}});
    const auto wb = TH::texelWeights(*bottomEdge, 4, 4, kClamp);
    const double expectB[4][4] = {{1, 1, 1, 1}, {0, 1, 1, 0}, {0, 1, 1, 0}, {0, 0, 0, 0}};
    // Mirrored in v: (0, .875) (.5, 0) (1, .875): the edge at v = .875 is a top edge: row 3 empty.
    osg::ref_ptr<osg::Geometry> topEdge =
        triangles({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 0.875f}, {0.5f, 0}, {1, 0.875f}});
    const auto wt = TH::texelWeights(*topEdge, 4, 4, kClamp);
    const double expectT[4][4] = {{0, 0, 0, 0}, {0, 1, 1, 0}, {0, 1, 1, 0}, {0, 0, 0, 0}};
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i)
        {
            EXPECT_DOUBLE_EQ(at(wb, i, j), expectB[j][i]) << i << "," << j;
            EXPECT_DOUBLE_EQ(at(wt, i, j), expectT[j][i]) << i << "," << j;
        }
}

TEST(TextureHistogramTest, DegenerateTrianglesGetZeroAndAddNothing)
{
    // The square (two triangles of object area 2, uv area .5) plus a third triangle.
    std::vector<osg::Vec3> p = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 0, 0}, {2, 2, 0}, {0, 2, 0}};
    std::vector<osg::Vec2> uv = {{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0, 1}};
    // (a) zero object area (collinear corners) with uv area .5 (the lower-left half): P^o = 0;
    // S^t sums to 1.5 so the square's triangles get P^t = 1/3, weights .5 / 3 = 1/6.
    auto pa = p;
    auto uva = uv;
    pa.insert(pa.end(), {{0, 0, 0}, {1, 1, 1}, {3, 3, 3}});
    uva.insert(uva.end(), {{0, 0}, {1, 0}, {0, 1}});
    const auto ta = TH::triangleAreas(*triangles(pa, uva));
    ASSERT_EQ(ta.size(), 3u);
    EXPECT_DOUBLE_EQ(ta[2].objectArea, 0.0);
    EXPECT_DOUBLE_EQ(ta[2].objectProportion, 0.0);
    EXPECT_DOUBLE_EQ(ta[2].textureArea, 0.5);
    EXPECT_DOUBLE_EQ(ta[2].textureProportion, 1.0 / 3.0);
    EXPECT_DOUBLE_EQ(ta[0].textureProportion, 1.0 / 3.0);
    EXPECT_DOUBLE_EQ(ta[0].objectProportion, 0.5);
    for (double v : TH::texelWeights(*triangles(pa, uva), 4, 4, kClamp))
        EXPECT_DOUBLE_EQ(v, 0.5 / 3.0);
    // (b) zero uv area (the uv diagonal, which passes through 4 texel centres) with object area
    // 2: P^t = 0, covers nothing; S^o sums to 6 so the square's triangles get P^o = 1/3.
    auto pb = p;
    auto uvb = uv;
    pb.insert(pb.end(), {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}});
    uvb.insert(uvb.end(), {{0, 0}, {0.5f, 0.5f}, {1, 1}});
    const auto tb = TH::triangleAreas(*triangles(pb, uvb));
    ASSERT_EQ(tb.size(), 3u);
    EXPECT_DOUBLE_EQ(tb[2].objectArea, 2.0);
    EXPECT_DOUBLE_EQ(tb[2].objectProportion, 1.0 / 3.0);
    EXPECT_DOUBLE_EQ(tb[2].textureArea, 0.0);
    EXPECT_DOUBLE_EQ(tb[2].textureProportion, 0.0);
    for (double v : TH::texelWeights(*triangles(pb, uvb), 4, 4, kClamp))
        EXPECT_DOUBLE_EQ(v, 1.0 / 6.0); // P^o (1/3) * P^t (1/2)
    // (c) a mesh of only degenerate triangles: all proportions 0 (zero sums), no weight.
    const auto tc =
        TH::triangleAreas(*triangles({{0, 0, 0}, {1, 1, 1}, {2, 2, 2}}, {{0, 0}, {1, 0}, {1, 1}}));
    EXPECT_DOUBLE_EQ(tc[0].objectProportion, 0.0);
    EXPECT_DOUBLE_EQ(tc[0].textureProportion, 1.0);
    EXPECT_EQ(TH::texelWeights(*triangles({{0, 0, 0}, {1, 1, 1}, {2, 2, 2}}, {{0, 0}, {1, 0}, {1, 1}}), 4, 4,
                               kClamp),
              std::vector<double>(16, 0.0));
}

TEST(TextureHistogramTest, RepeatedAndNegativeCoordinates)
{
    // uv [0, 2] x [0, 1] on REPEAT: every texel covered twice (once per period): 2 * .25.
    osg::ref_ptr<osg::Geometry> g = quad(0, 0, 2, 1);
    const auto r = TH::texCoordRange(*g);
    ASSERT_TRUE(r.valid);
    EXPECT_EQ(r.uMin, 0.0);
    EXPECT_EQ(r.uMax, 2.0);
    EXPECT_EQ(r.vMin, 0.0);
    EXPECT_EQ(r.vMax, 1.0);
    EXPECT_EQ(r.periodsU(), 2);
    EXPECT_EQ(r.periodsV(), 1);
    EXPECT_DOUBLE_EQ(TH::triangleAreas(*g)[0].textureArea, 1.0);
    EXPECT_EQ(TH::texelWeights(*g, 4, 4, kRepeat), std::vector<double>(16, 0.5));
    // MIRROR: the second period is the first mirrored; uniform coverage stays 2 * .25.
    EXPECT_EQ(TH::texelWeights(*g, 4, 4, kMirror), std::vector<double>(16, 0.5));
    // uv [-1, 0] x [0, 1]: the same weights as [0, 1].
    osg::ref_ptr<osg::Geometry> n = quad(-1, 0, 0, 1);
    const auto rn = TH::texCoordRange(*n);
    EXPECT_EQ(rn.uMin, -1.0);
    EXPECT_EQ(rn.uMax, 0.0);
    EXPECT_EQ(rn.u0, -1);
    EXPECT_EQ(rn.u1, 0);
    EXPECT_EQ(TH::texelWeights(*n, 4, 4, kRepeat), TH::texelWeights(*quad(0, 0, 1, 1), 4, 4, kRepeat));
    // uv [-1.5, 2.5] x [-1, 0]: range [-2, 3] x [-1, 0]; 16 covered columns fold 4 times onto
    // each texel column: 4 * .25.
    osg::ref_ptr<osg::Geometry> w = quad(-1.5f, -1, 2.5f, 0);
    const auto rw = TH::texCoordRange(*w);
    EXPECT_EQ(rw.u0, -2);
    EXPECT_EQ(rw.u1, 3);
    EXPECT_EQ(rw.v0, -1);
    EXPECT_EQ(rw.v1, 0);
    EXPECT_EQ(rw.periodsU(), 5);
    EXPECT_EQ(TH::texelWeights(*w, 4, 4, kRepeat), std::vector<double>(16, 1.0));
}

TEST(TextureHistogramTest, ClampPilesTheOutsideOntoTheBorderTexels)
{
    // uv [0, 2] on CLAMP: virtual columns 0..7 each get .25 per row; columns 4..7 (u > 1) read
    // the border column 3: columns 0-2 get .25, column 3 gets .25 + 4 * .25 = 1.25.
    const auto w = TH::texelWeights(*quad(0, 0, 2, 1), 4, 4, kClamp);
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i)
            EXPECT_DOUBLE_EQ(at(w, i, j), i == 3 ? 1.25 : 0.25) << i << "," << j;
    // uv [-1, 0] on CLAMP: all four virtual columns read column 0: 4 * .25 = 1 there.
    const auto n = TH::texelWeights(*quad(-1, 0, 0, 1), 4, 4, kClamp);
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i)
            EXPECT_DOUBLE_EQ(at(n, i, j), i == 0 ? 1.0 : 0.0) << i << "," << j;
}

TEST(TextureHistogramTest, ObjectAreaWeightsTheTexels)
{
    // Equal uv halves of [0, 1]^2, object areas 1 and 3: P^o .25 / .75, P^t .5 / .5.
    // The lower-right uv half (u > v, plus the diagonal: its left edge) gets .125, 10 texels;
    // the upper-left (u < v) .375, 6 texels.
    osg::ref_ptr<osg::Geometry> g =
        triangles({{0, 0, 0}, {1, 0, 0}, {1, 2, 0}, {0, 0, 0}, {3, 0, 0}, {0, 2, 0}},
                  {{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0, 1}});
    const auto t = TH::triangleAreas(*g);
    ASSERT_EQ(t.size(), 2u);
    EXPECT_DOUBLE_EQ(t[0].objectArea, 1.0);
    EXPECT_DOUBLE_EQ(t[1].objectArea, 3.0);
    EXPECT_DOUBLE_EQ(t[0].objectProportion, 0.25);
    EXPECT_DOUBLE_EQ(t[1].objectProportion, 0.75);
    EXPECT_DOUBLE_EQ(t[0].textureProportion, 0.5);
    EXPECT_DOUBLE_EQ(t[1].textureProportion, 0.5);
    const auto w = TH::texelWeights(*g, 4, 4, kRepeat);
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i)
            EXPECT_DOUBLE_EQ(at(w, i, j), i >= j ? 0.125 : 0.375) << i << "," << j;
    EXPECT_DOUBLE_EQ(std::accumulate(w.begin(), w.end(), 0.0), 10 * 0.125 + 6 * 0.375);
}

TEST(TextureHistogramTest, ColorTableUnifiesColoursAndSumsWeights)
{
    // 4 x 4 RGB: row 0 red, rows 1-2 green, row 3 blue except texel (3, 3) red.
    osg::ref_ptr<osg::Image> img = new osg::Image;
    img->allocateImage(4, 4, 1, GL_RGB, GL_UNSIGNED_BYTE);
    std::vector<double> w(16);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x)
        {
            unsigned char* p = img->data(x, y);
            const bool red = y == 0 || (x == 3 && y == 3), green = !red && (y == 1 || y == 2);
            p[0] = red ? 255 : 0;
            p[1] = green ? 200 : 0;
            p[2] = (!red && !green) ? 10 : 0;
            w[std::size_t(y * 4 + x)] = 0.5 * x; // column 0 weighs nothing
        }
    w[15] = 4.0;
    // red: row 0 (0 + .5 + 1 + 1.5 = 3) + (3, 3) 4 = 7; green: 2 * 3 = 6; blue: row 3 x<3 = 1.5.
    const auto t = TH::colorTable(*img, w);
    ASSERT_EQ(t.size(), 3u);
    EXPECT_EQ(t[0].r, 255);
    EXPECT_EQ(t[0].g, 0);
    EXPECT_DOUBLE_EQ(t[0].weight, 7.0);
    EXPECT_EQ(t[1].g, 200);
    EXPECT_DOUBLE_EQ(t[1].weight, 6.0);
    EXPECT_EQ(t[2].b, 10);
    EXPECT_DOUBLE_EQ(t[2].weight, 1.5);
    // A colour whose texels all weigh 0 is left out: blue with row 3 weights zeroed.
    w[12] = w[13] = w[14] = 0;
    EXPECT_EQ(TH::colorTable(*img, w).size(), 2u);
    // Equal weights: colour order (0,200,0) before (255,0,0).
    std::vector<double> eq(16, 0.0);
    eq[0] = 1.0; // red
    eq[4] = 1.0; // green
    const auto te = TH::colorTable(*img, eq);
    ASSERT_EQ(te.size(), 2u);
    EXPECT_EQ(te[0].r, 0);
    EXPECT_EQ(te[1].r, 255);
    // BGRA reads its channels in its own order.
    osg::ref_ptr<osg::Image> bgra = new osg::Image;
    bgra->allocateImage(1, 1, 1, GL_BGRA, GL_UNSIGNED_BYTE);
    unsigned char* q = bgra->data();
    q[0] = 1;
    q[1] = 2;
    q[2] = 3;
    q[3] = 4;
    const auto tb = TH::colorTable(*bgra, {2.0});
    ASSERT_EQ(tb.size(), 1u);
    EXPECT_EQ(tb[0].r, 3);
    EXPECT_EQ(tb[0].b, 1);
}

TEST(TextureHistogramTest, SceneWeightsSumGeometriesPerImage)
{
    // Two geometries under a group whose StateSet has a REPEAT 4 x 4 texture: the square [0,1]^2
    // (.25 everywhere) and the lower-left right triangle (1 on 6 texels); each normalized alone.
    osg::ref_ptr<osg::Image> img = new osg::Image;
    img->allocateImage(4, 4, 1, GL_RGBA, GL_UNSIGNED_BYTE);
    osg::ref_ptr<osg::Texture2D> tex = new osg::Texture2D(img.get());
    tex->setWrap(osg::Texture::WRAP_S, osg::Texture::REPEAT);
    tex->setWrap(osg::Texture::WRAP_T, osg::Texture::REPEAT);
    osg::ref_ptr<osg::Group> root = new osg::Group;
    osg::ref_ptr<osg::Group> textured = new osg::Group;
    textured->getOrCreateStateSet()->setTextureAttributeAndModes(0, tex.get());
    root->addChild(textured.get());
    textured->addChild(quad(0, 0, 1, 1));
    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    geode->addDrawable(triangles({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 0}, {1, 0}, {0, 1}}));
    textured->addChild(geode.get());
    root->addChild(quad(0, 0, 1, 1)); // untextured: ignored
    const auto m = TH::sceneWeights(*root);
    ASSERT_EQ(m.size(), 1u);
    ASSERT_EQ(m.begin()->first, img.get());
    const auto& w = m.begin()->second;
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i)
            EXPECT_DOUBLE_EQ(at(w, i, j), 0.25 + (i + j <= 2 ? 1.0 : 0.0)) << i << "," << j;
}

TEST(TextureHistogramTest, BadInputIsRefusedNamingIt)
{
    osg::ref_ptr<osg::Geometry> g = quad(0, 0, 1, 1);
    osg::ref_ptr<osg::Geometry> noUv = new osg::Geometry(*g, osg::CopyOp::SHALLOW_COPY);
    noUv->setTexCoordArray(0, nullptr);
    try
    {
        TH::triangleAreas(*noUv);
        FAIL() << "no texcoords accepted";
    }
    catch (const std::invalid_argument& e)
    {
        EXPECT_NE(std::string(e.what()).find("no texture coordinates on unit 0"), std::string::npos)
            << e.what();
    }
    EXPECT_THROW(TH::texelWeights(*g, 4, 4, kClamp, 1), std::invalid_argument); // unit 1 has none
    osg::ref_ptr<osg::Geometry> noV = new osg::Geometry(*g, osg::CopyOp::SHALLOW_COPY);
    noV->setVertexArray(nullptr);
    try
    {
        TH::triangleAreas(*noV);
        FAIL();
    }
    catch (const std::invalid_argument& e)
    {
        EXPECT_NE(std::string(e.what()).find("no vertex array"), std::string::npos) << e.what();
    }
    osg::ref_ptr<osg::Geometry> mismatch = new osg::Geometry(*g, osg::CopyOp::SHALLOW_COPY);
    osg::ref_ptr<osg::Vec2Array> three = new osg::Vec2Array(3);
    mismatch->setTexCoordArray(0, three.get());
    try
    {
        TH::triangleAreas(*mismatch);
        FAIL();
    }
    catch (const std::invalid_argument& e)
    {
        EXPECT_NE(std::string(e.what()).find("does not match vertex count 4"), std::string::npos) << e.what();
    }
    try
    {
        TH::texelWeights(*g, 0, 4, kClamp);
        FAIL();
    }
    catch (const std::invalid_argument& e)
    {
        EXPECT_NE(std::string(e.what()).find("width"), std::string::npos) << e.what();
    }
    // 2^21 texels per axis: refused naming the range.
    try
    {
        TH::texelWeights(*quad(0, 0, 2048, 1), 1024, 4, kRepeat);
        FAIL();
    }
    catch (const std::invalid_argument& e)
    {
        EXPECT_NE(std::string(e.what()).find("range u [0.000000, 2048.000000]"), std::string::npos)
            << e.what();
    }
    // A compressed format other than S3TC is refused, naming it.
    osg::ref_ptr<osg::Image> rgtc = new osg::Image;
    std::vector<unsigned char>* blocks = new std::vector<unsigned char>(8, 0);
    rgtc->setImage(4, 4, 1, GL_COMPRESSED_RED_RGTC1_EXT, GL_COMPRESSED_RED_RGTC1_EXT, GL_UNSIGNED_BYTE,
                   blocks->data(), osg::Image::NO_DELETE);
    try
    {
        TH::colorTable(*rgtc, std::vector<double>(16, 1.0));
        ADD_FAILURE() << "an RGTC image was accepted";
    }
    catch (const std::invalid_argument& e)
    {
        EXPECT_NE(std::string(e.what()).find("0x8dbb"), std::string::npos) << e.what();
    }
    delete blocks;
    osg::ref_ptr<osg::Image> rgb = new osg::Image;
    rgb->allocateImage(2, 2, 1, GL_RGB, GL_UNSIGNED_BYTE);
    EXPECT_THROW(TH::colorTable(*rgb, std::vector<double>(3, 1.0)), std::invalid_argument);
    EXPECT_THROW(TH::colorTable(*rgb, {1.0, -1.0, 0.0, 0.0}), std::invalid_argument);
}

// Any texture format a model brings (issue: "--style palette on a model with a luminance texture
// aborts the whole render"): luminance, luminance-alpha and S3TC images give the colour table of
// the colours a shader samples from them, counted by hand.
TEST(TextureHistogramTest, ColorTableReadsLuminanceLuminanceAlphaAndS3TC)
{
    osg::ref_ptr<osg::Image> grey = new osg::Image;
    grey->allocateImage(2, 2, 1, GL_LUMINANCE, GL_UNSIGNED_BYTE);
    const unsigned char g[4] = {10, 10, 200, 77};
    std::copy(g, g + 4, grey->data());
    auto t = TH::colorTable(*grey, {1.0, 2.0, 0.5, 0.0});
    ASSERT_EQ(t.size(), 2u); // 77 has weight 0
    EXPECT_EQ(int(t[0].r), 10);
    EXPECT_EQ(int(t[0].g), 10);
    EXPECT_EQ(int(t[0].b), 10);
    EXPECT_DOUBLE_EQ(t[0].weight, 3.0);
    EXPECT_EQ(int(t[1].r), 200);
    EXPECT_EQ(int(t[1].b), 200);
    EXPECT_DOUBLE_EQ(t[1].weight, 0.5);

    osg::ref_ptr<osg::Image> la = new osg::Image;
    la->allocateImage(2, 1, 1, GL_LUMINANCE_ALPHA, GL_UNSIGNED_BYTE);
    const unsigned char l[4] = {50, 255, 50, 0};
    std::copy(l, l + 4, la->data());
    t = TH::colorTable(*la, {1.0, 1.0});
    ASSERT_EQ(t.size(), 1u); // alpha is ignored: one colour (50, 50, 50)
    EXPECT_EQ(int(t[0].g), 50);
    EXPECT_DOUBLE_EQ(t[0].weight, 2.0);

    // One DXT1 block: colour 0 = pure red (565 0xF800), colour 1 = pure blue (0x001F); row y of
    // the block uses index y, so rows are red, blue, 2/3 red + 1/3 blue, 1/3 red + 2/3 blue
    // (the S3TC four-colour mode, colour 0 > colour 1).
    unsigned char block[8] = {0x00, 0xF8, 0x1F, 0x00, 0x00, 0x55, 0xAA, 0xFF};
    osg::ref_ptr<osg::Image> dxt = new osg::Image;
    dxt->setImage(4, 4, 1, GL_COMPRESSED_RGB_S3TC_DXT1_EXT, GL_COMPRESSED_RGB_S3TC_DXT1_EXT, GL_UNSIGNED_BYTE,
                  block, osg::Image::NO_DELETE);
    std::vector<double> w(16, 1.0);
    for (int x = 0; x < 4; ++x)
        w[std::size_t(x)] = 4.0; // row 0 (red) weighs most
    t = TH::colorTable(*dxt, w);
    ASSERT_EQ(t.size(), 4u);
    EXPECT_EQ(int(t[0].r), 255);
    EXPECT_EQ(int(t[0].g), 0);
    EXPECT_EQ(int(t[0].b), 0);
    EXPECT_DOUBLE_EQ(t[0].weight, 16.0);
    // The other three rows weigh 4 each, sorted by colour: (0,0,255), ~(85,0,170), ~(170,0,85).
    // S3TC leaves the rounding of the interpolated colours to the decoder (OSG's reference decoder
    // interpolates the 5-bit values: 82 and 173); tolerance 4.
    EXPECT_EQ(int(t[1].r), 0);
    EXPECT_EQ(int(t[1].b), 255);
    EXPECT_NEAR(int(t[2].r), 85, 4);
    EXPECT_NEAR(int(t[2].b), 170, 4);
    EXPECT_NEAR(int(t[3].r), 170, 4);
    EXPECT_NEAR(int(t[3].b), 85, 4);
}
