// ViewpointEntropy: face merging, the entropy formula, and best views of shapes whose answer is
// known, rendered headless as ID buffers (needs an OpenGL context: label gl).
#include "support/TestSupport.h"

#include <osgLoA/city/CityGenerator>
#include <osgLoA/semantics/FeatureIndex>
#include <osgLoA/semantics/ViewpointEntropy>

#include <osg/Geode>
#include <osg/Geometry>
#include <osg/Group>
#include <osg/MatrixTransform>
#include <osg/io_utils>

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>

using namespace osgLoA;

namespace
{
/** Triangles as a plain vertex list (3 per triangle), to be wrapped in a Geometry. */
struct Mesh
{
    std::vector<osg::Vec3> v;

    void triangle(const osg::Vec3& a, const osg::Vec3& b, const osg::Vec3& c)
    {
        v.insert(v.end(), {a, b, c});
    }
    /** A planar quad a-b-c-d (counter-clockwise seen from outside), split into nu x nv cells of two
     *  triangles each (a conforming grid: every inner edge is shared by two triangles). */
    void quad(const osg::Vec3& a, const osg::Vec3& b, const osg::Vec3& c, const osg::Vec3& d, int nu = 1,
              int nv = 1)
    {
        auto at = [&](float s, float t)
        { return a * ((1 - s) * (1 - t)) + b * (s * (1 - t)) + c * (s * t) + d * ((1 - s) * t); };
        for (int i = 0; i < nu; ++i)
            for (int j = 0; j < nv; ++j)
            {
                const float s0 = float(i) / nu, s1 = float(i + 1) / nu, t0 = float(j) / nv,
                            t1 = float(j + 1) / nv;
                triangle(at(s0, t0), at(s1, t0), at(s1, t1));
                triangle(at(s0, t0), at(s1, t1), at(s0, t1));
            }
    }
    /** An axis-aligned box; splitTop splits the +Z face into splitTop x splitTop cells. */
    void box(const osg::Vec3& lo, const osg::Vec3& hi, int splitTop = 1)
    {
        const float x0 = lo.x(), y0 = lo.y(), z0 = lo.z(), x1 = hi.x(), y1 = hi.y(), z1 = hi.z();
        quad({x0, y0, z0}, {x0, y1, z0}, {x1, y1, z0}, {x1, y0, z0});                     // -Z
        quad({x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1}, splitTop, splitTop); // +Z
        quad({x0, y0, z0}, {x1, y0, z0}, {x1, y0, z1}, {x0, y0, z1});                     // -Y
        quad({x1, y1, z0}, {x0, y1, z0}, {x0, y1, z1}, {x1, y1, z1});                     // +Y
        quad({x0, y1, z0}, {x0, y0, z0}, {x0, y0, z1}, {x0, y1, z1});                     // -X
        quad({x1, y0, z0}, {x1, y1, z0}, {x1, y1, z1}, {x1, y0, z1});                     // +X
    }

    osg::ref_ptr<osg::Geode> geode() const
    {
        osg::ref_ptr<osg::Geometry> g = new osg::Geometry;
        g->setVertexArray(new osg::Vec3Array(v.begin(), v.end()));
        g->addPrimitiveSet(new osg::DrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(v.size())));
        osg::ref_ptr<osg::Geode> geode = new osg::Geode;
        geode->addDrawable(g.get());
        return geode;
    }
};

unsigned faceCount(const Mesh& m)
{
    return ViewpointEntropy::mergeFaces(m.v).count;
}

/** A 20 x 4 x 20 m slab centred on the origin in plan, standing on z = 0, whose +Y facade
 *  carries a 12 x 12 grid of 1.3 m x 1.3 m reliefs (a pitch of 20/12 m) protruding 5 cm; the
 *  other facades and the roof are plain. 6 + 144 * 6 faces.
 *
 *  Why this shape: viewpoint entropy rewards every face that comes into view. Turning away
 *  from the facade's normal brings in a plain side wall and the reliefs' sides, while the
 *  reliefs' fronts shrink with cos(angle). Measured at 128 x 128, 10 degrees elevation: with
 *  0.15 m deep reliefs or a 6 m deep slab the maximum moves 20 to 40 degrees off the normal;
 *  with this shallow slab and 5 cm reliefs the normal view is the maximum (3.67 bits against
 *  3.59 at +-10 and 3.55 at +-20 degrees). The test therefore checks the metric, not a
 *  belief that "the detailed side" always wins. */
Mesh detailedSlab()
{
    Mesh m;
    m.box({-10, -2, 0}, {10, 2, 20});
    const float pitch = 20.0f / 12.0f, size = 1.3f, depth = 0.05f;
    for (int i = 0; i < 12; ++i)
        for (int j = 0; j < 12; ++j)
        {
            const float x = -10.0f + pitch * (i + 0.5f) - size / 2, z = pitch * (j + 0.5f) - size / 2;
            m.box({x, 2.0f, z}, {x + size, 2.0f + depth, z + size});
        }
    return m;
}

double angleDegrees(const osg::Vec3& a, const osg::Vec3& b)
{
    return osg::RadiansToDegrees(
        std::acos(std::max(-1.0f, std::min(1.0f, a * b / (a.length() * b.length())))));
}

void printEntropies(const std::string& what, const ViewpointEntropy::Result& r)
{
    std::cout << what << ": " << r.faces << " faces, best " << r.bestIndex << " (" << r.bestDirection
              << ")\n ";
    for (std::size_t k = 0; k < r.entropies.size(); ++k)
        std::cout << " " << std::fixed << std::setprecision(3) << r.entropies[k];
    std::cout << std::endl;
}
} // namespace

// (e) H = -sum p log2 p over faces and background, p = area / total.
TEST(ViewpointEntropyGLTest, EntropyOfHandComputedHistograms)
{
    // Areas 1, 1 and background 2 of a total 4: p = 1/4, 1/4, 1/2, so
    // H = 2 * (1/4 * log2 4) + 1/2 * log2 2 = 2 * 0.5 + 0.5 = 1.5 bits.
    EXPECT_DOUBLE_EQ(ViewpointEntropy::entropy({1, 1}, 2), 1.5);
    // Four equal faces filling the image: log2 4 = 2 bits.
    EXPECT_DOUBLE_EQ(ViewpointEntropy::entropy({3, 3, 3, 3}, 0), 2.0);
    // One face covering everything, or nothing but background: no uncertainty, 0 bits.
    EXPECT_DOUBLE_EQ(ViewpointEntropy::entropy({5}, 0), 0.0);
    EXPECT_DOUBLE_EQ(ViewpointEntropy::entropy({}, 7), 0.0);
    EXPECT_DOUBLE_EQ(ViewpointEntropy::entropy({0, 0}, 0), 0.0);
    // Empty faces add nothing: {1, 0, 1} with background 2 is still 1.5 bits.
    EXPECT_DOUBLE_EQ(ViewpointEntropy::entropy({1, 0, 1}, 2), 1.5);
    // Binary entropy h(1/8) = 1/8 log2 8 + 7/8 log2(8/7).
    EXPECT_NEAR(ViewpointEntropy::entropy({1}, 7), 0.375 + 0.875 * std::log2(8.0 / 7.0), 1e-12);
    EXPECT_THROW(ViewpointEntropy::entropy({-1}, 2), std::invalid_argument);
    EXPECT_THROW(ViewpointEntropy::entropy({1}, std::nan("")), std::invalid_argument);
}

// (d) Coplanar, edge-connected triangles are one face.
TEST(ViewpointEntropyGLTest, CoplanarConnectedTrianglesMergeIntoFaces)
{
    Mesh quad;
    quad.quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0});
    EXPECT_EQ(faceCount(quad), 1u); // two triangles, one face

    Mesh cube;
    cube.box({0, 0, 0}, {1, 1, 1});
    EXPECT_EQ(ViewpointEntropy::mergeFaces(cube.v).triangles(), 12u);
    EXPECT_EQ(faceCount(cube), 6u);

    Mesh split; // the top face as a 2 x 2 grid of cells: 8 triangles
    split.box({0, 0, 0}, {1, 1, 1}, 2);
    EXPECT_EQ(ViewpointEntropy::mergeFaces(split.v).triangles(), 18u);
    EXPECT_EQ(faceCount(split), 6u);

    // Coplanar but apart: two faces. Connected but folded by 90 degrees: two faces.
    Mesh apart;
    apart.quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0});
    apart.quad({2, 0, 0}, {3, 0, 0}, {3, 1, 0}, {2, 1, 0});
    EXPECT_EQ(faceCount(apart), 2u);
    Mesh folded;
    folded.quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0});
    folded.quad({0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1});
    EXPECT_EQ(faceCount(folded), 2u);

    // Shared positions within epsilon (1 mm by default) still connect; 1 cm apart does not.
    Mesh nearly;
    nearly.triangle({0, 0, 0}, {1, 0, 0}, {1, 1, 0});
    nearly.triangle({0.0001f, 0, 0}, {1, 1.0001f, 0}, {0, 1, 0});
    EXPECT_EQ(faceCount(nearly), 1u);
    Mesh gap;
    gap.triangle({0, 0, 0}, {1, 0, 0}, {1, 1, 0});
    gap.triangle({0.01f, 0, 0}, {1, 1, 0}, {0, 1, 0});
    EXPECT_EQ(faceCount(gap), 2u);

    // Degenerate triangles are dropped.
    Mesh degenerate;
    degenerate.triangle({0, 0, 0}, {1, 0, 0}, {2, 0, 0});
    degenerate.triangle({0, 0, 0}, {0, 0, 0}, {0, 1, 0});
    EXPECT_EQ(faceCount(degenerate), 0u);

    // The test slab: 6 walls + 144 reliefs x 6 faces (their backs are separate faces too).
    EXPECT_EQ(faceCount(detailedSlab()), 6u + 144u * 6u);
}

// (a) The detail is on +Y: the viewer at +Y (looking towards -Y) sees the most faces.
TEST(ViewpointEntropyGLTest, BestViewFacesTheDetailedFacade)
{
    osg::ref_ptr<osg::Geode> slab = detailedSlab().geode();
    osg::ref_ptr<ViewpointEntropy> ve = new ViewpointEntropy;
    const ViewpointEntropy::Result r = ve->evaluate(*slab, osg::NodePath{slab.get()});
    printEntropies("+Y facade", r);
    ASSERT_TRUE(r.valid);
    EXPECT_EQ(r.invalidPixels, 0u);
    ASSERT_EQ(r.entropies.size(), 36u);
    EXPECT_NEAR(r.bestDirection.length(), 1.0f, 1e-6f);
    EXPECT_EQ(r.bestDirection.z(), 0.0f);
    EXPECT_LE(angleDegrees(r.bestDirection, osg::Vec3(0, 1, 0)), 10.0 + 1e-3) << r.bestDirection;
}

// (b) The same slab turned by +90 degrees about Z through a transform above the feature: the
// detail faces -X, and so must the best view; the world matrix of the path is applied.
TEST(ViewpointEntropyGLTest, BestViewFollowsTheWorldTransform)
{
    osg::ref_ptr<osg::Group> root = new osg::Group;
    osg::ref_ptr<osg::MatrixTransform> xf = new osg::MatrixTransform(osg::Matrix::rotate(osg::PI_2, 0, 0, 1) *
                                                                     osg::Matrix::translate(500, -200, 30));
    root->addChild(xf);
    osg::ref_ptr<osg::Geode> slab = detailedSlab().geode();
    xf->addChild(slab);
    osg::ref_ptr<ViewpointEntropy> ve = new ViewpointEntropy;
    const ViewpointEntropy::Result r = ve->evaluate(*slab, osg::NodePath{root.get(), xf.get(), slab.get()});
    printEntropies("-X facade", r);
    ASSERT_TRUE(r.valid);
    EXPECT_EQ(r.invalidPixels, 0u);
    // The slab spans x in [-2.05, 2] after the turn (the reliefs stick out 5 cm towards -X).
    EXPECT_NEAR(r.center.x(), 500.0 - 0.025, 1e-3);
    EXPECT_NEAR(r.center.y(), -200.0, 1e-3);
    EXPECT_NEAR(r.center.z(), 40.0, 1e-3);
    EXPECT_LE(angleDegrees(r.bestDirection, osg::Vec3(-1, 0, 0)), 10.0 + 1e-3) << r.bestDirection;
    // The path may also end above the feature's root: same result.
    const ViewpointEntropy::Result r2 = ve->evaluate(*slab, osg::NodePath{root.get(), xf.get()});
    EXPECT_EQ(r2.entropies, r.entropies);
}

// (c) A box square in plan, seen horizontally (elevation 0) from 8 directions 45 degrees apart.
//
// Axis views (0, 90, 180, 270 degrees) see one face (the eye is inside the slabs of the side
// walls, roof and floor, so those are back-facing and hidden): with p the face's share of the
// image, H_axis = h(p) = -p log2 p - (1-p) log2(1-p). The box is symmetric under quarter turns
// about the vertical axis through its centre, so the four axis images are the same image and
// their entropies are equal (up to rasterization rounding: tolerance 1e-3 bits).
// Diagonal views (45 degrees, ...) see two faces of equal projected area; the silhouette is
// wider by sqrt(2) (the diagonal of the plan instead of its side), so the object's share is
// q ~ sqrt(2) p split into two halves: H_diag = h(q) + q (the split adds q * 1 bit). For q <= 1/2,
// h is increasing, so h(q) > h(p) already; for q > 1/2, h(q) + q >= 1 >= h(p). Hence
// H_diag > H_axis for every size (perspective changes the sqrt(2) a little, not the order).
TEST(ViewpointEntropyGLTest, SquareBoxIsSymmetricAndDiagonalViewsWin)
{
    Mesh m;
    m.box({-5, -5, -5}, {5, 5, 5});
    osg::ref_ptr<osg::Geode> box = m.geode();
    ViewpointEntropy::Settings s;
    s.directions = 8;
    s.elevationDegrees = 0.0;
    osg::ref_ptr<ViewpointEntropy> ve = new ViewpointEntropy(s);
    const ViewpointEntropy::Result r = ve->evaluate(*box, osg::NodePath{box.get()});
    printEntropies("square box", r);
    ASSERT_TRUE(r.valid);
    ASSERT_EQ(r.entropies.size(), 8u);
    EXPECT_EQ(r.invalidPixels, 0u);
    for (unsigned k : {2u, 4u, 6u})
        EXPECT_NEAR(r.entropies[k], r.entropies[0], 1e-3) << k;
    for (unsigned k : {0u, 2u, 4u, 6u})
    {
        EXPECT_EQ(r.visibleFaces[k], 1u) << k;
        EXPECT_EQ(r.visibleFaces[k + 1], 2u) << k + 1;
        EXPECT_GT(r.entropies[k + 1], r.entropies[k] + 0.1) << k;
    }
    // All four diagonals tie (within rounding); the first maximum in ring order is one of them.
    EXPECT_EQ(r.bestIndex % 2, 1u);
}

// (f) No triangles: no best view, no crash, no rendering.
TEST(ViewpointEntropyGLTest, EmptyGeometryHasNoBestView)
{
    osg::ref_ptr<osg::Group> root = new osg::Group;
    osg::ref_ptr<osg::Group> featureNode = new osg::Group;
    featureNode->addChild(new osg::Geode);
    osg::ref_ptr<osg::Geode> degenerate = Mesh().geode();
    featureNode->addChild(degenerate);
    root->addChild(featureNode);
    osg::ref_ptr<Feature> f = new Feature(1, FeatureType::Building);
    f->setLandmark(true);
    f->setBestViewDirection(osg::Vec3(1, 0, 0)); // stale: must be cleared
    Feature::attach(*featureNode, f.get());

    osg::ref_ptr<ViewpointEntropy> ve = new ViewpointEntropy;
    const ViewpointEntropy::Result r =
        ve->evaluate(*featureNode, osg::NodePath{root.get(), featureNode.get()});
    EXPECT_FALSE(r.valid);
    EXPECT_EQ(r.faces, 0u);
    EXPECT_TRUE(r.entropies.empty());
    EXPECT_FALSE(r.message.empty());

    FeatureIndex index(*root);
    std::vector<ViewpointEntropy::Result> results;
    EXPECT_EQ(ve->computeBestViews(index, &results), 0u);
    ASSERT_EQ(results.size(), 1u);
    EXPECT_FALSE(results[0].valid);
    EXPECT_FALSE(f->hasBestView());
}

TEST(ViewpointEntropyGLTest, BadSettingsAreRejected)
{
    ViewpointEntropy::Settings s;
    s.directions = 0;
    EXPECT_THROW(osg::ref_ptr<ViewpointEntropy>(new ViewpointEntropy(s)), std::invalid_argument);
    s = ViewpointEntropy::Settings();
    s.elevationDegrees = 90.0;
    EXPECT_THROW(osg::ref_ptr<ViewpointEntropy>(new ViewpointEntropy(s)), std::invalid_argument);
    s = ViewpointEntropy::Settings();
    s.fovyDegrees = 0.0;
    EXPECT_THROW(osg::ref_ptr<ViewpointEntropy>(new ViewpointEntropy(s)), std::invalid_argument);
    s = ViewpointEntropy::Settings();
    s.width = 0;
    EXPECT_THROW(osg::ref_ptr<ViewpointEntropy>(new ViewpointEntropy(s)), std::invalid_argument);
}

// The demo city: every landmark gets a unit horizontal best view, no other feature gets one,
// and every ID buffer is exact.
TEST(ViewpointEntropyGLTest, DemoCityLandmarksGetBestViews)
{
    osg::ref_ptr<osg::Group> city = CityGenerator(CityParameters::small()).generate();
    FeatureIndex index(*city);
    unsigned landmarks = 0;
    for (const FeatureIndex::Entry& e : index.entries())
    {
        EXPECT_FALSE(e.feature->hasBestView());
        if (e.feature->getLandmark()) ++landmarks;
    }
    ASSERT_GT(landmarks, 0u);
    osg::ref_ptr<ViewpointEntropy> ve = new ViewpointEntropy;
    std::vector<ViewpointEntropy::Result> results;
    const auto t0 = std::chrono::steady_clock::now();
    EXPECT_EQ(ve->computeBestViews(index, &results), landmarks);
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    std::cout << "computeBestViews: " << landmarks << " landmarks, " << std::fixed << std::setprecision(1)
              << ms << " ms (36 directions at 128x128)\n";
    for (const ViewpointEntropy::Result& r : results)
    {
        std::cout << "  landmark " << r.featureId << ": " << r.triangles << " triangles, " << r.faces
                  << " faces, " << r.milliseconds << " ms, best " << r.bestIndex * 10
                  << " deg, H = " << r.entropies[r.bestIndex] << " bits\n";
        EXPECT_TRUE(r.valid);
        EXPECT_EQ(r.invalidPixels, 0u) << r.featureId;
    }
    for (const FeatureIndex::Entry& e : index.entries())
    {
        const Feature& f = *e.feature;
        if (f.getLandmark())
        {
            ASSERT_TRUE(f.hasBestView()) << f.getId();
            EXPECT_NEAR(f.getBestViewDirection().length(), 1.0f, 1e-6f) << f.getId();
            EXPECT_EQ(f.getBestViewDirection().z(), 0.0f) << f.getId();
        }
        else
            EXPECT_FALSE(f.hasBestView()) << f.getId();
    }
}
