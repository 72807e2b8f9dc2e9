// LandmarkDeformation (paper 004 §3.2.2, Figure 7) on the CPU: each step against hand-computed
// vertices of a 10 x 20 x 30 box, the blend, the matrix against the steps, the fallbacks
// (straight-down camera, no best view, degenerate boxes), non-landmark sinking, validation,
// the uniforms, and write-read-write round trips of the serializer wrapper.
#include "support/TestSupport.h"

#include <osgLoA/transitions/LandmarkDeformation>
#include <osgLoA/transitions/ScenarioLibrary>
#include <osgLoA/transitions/UsageScenario>

#include <osg/Uniform>
#include <osgDB/ReadFile>
#include <osgDB/WriteFile>

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>

using namespace osgLoA;

namespace
{
typedef LandmarkDeformation LD;
constexpr double kPi = 3.14159265358979323846;

// The test box: 10 x 20 x 30 at (100..110, 200..220, 0..30); centre c = (105, 210, 15),
// footprint centre b = (105, 210, 0).
const osg::BoundingBoxd kBox(100, 200, 0, 110, 220, 30);
const osg::Vec3d kCentre(105, 210, 15);

LD::FeatureInput landmark(const osg::Vec3d& bestView = osg::Vec3d(), double interest = 1.0,
                          const osg::BoundingBoxd& box = kBox)
{
    LD::FeatureInput in;
    in.bound = box;
    in.landmark = true;
    in.bestView = bestView;
    in.staticInterest = interest;
    in.type = FeatureType::Building;
    return in;
}

/** Only the named steps on; the driver a step at distance 1 (map-likeness 1 beyond 1 m). */
osg::ref_ptr<LD> only(bool scale, bool rotate, bool flatten, bool billboard)
{
    osg::ref_ptr<LD> d = new LD;
    d->setScalingEnabled(scale);
    d->setRotationEnabled(rotate);
    d->setFlatteningEnabled(flatten);
    d->setBillboardEnabled(billboard);
    d->setDriverKind(SaliencyMetric::VIEW_DISTANCE);
    d->setDriverNear(0.0);
    d->setDriverFar(1.0);
    d->setMaxTiltDegrees(90.0);
    return d;
}

bool finite(const osg::Vec3d& v)
{
    return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z());
}

bool finite(const osg::Matrixd& m)
{
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c)
            if (!std::isfinite(m(r, c))) return false;
    return true;
}

#define EXPECT_VEC_NEAR(a, b, tol)                                                                           \
    do                                                                                                       \
    {                                                                                                        \
        const osg::Vec3d _a = (a), _b = (b);                                                                 \
        EXPECT_NEAR(_a.x(), _b.x(), tol) << #a;                                                              \
        EXPECT_NEAR(_a.y(), _b.y(), tol) << #a;                                                              \
        EXPECT_NEAR(_a.z(), _b.z(), tol) << #a;                                                              \
    } while (0)

/** Both forms of the deformation (the steps and the matrix) give want. */
void expectDeformed(const LD::FeatureFrame& f, const osg::Vec3d& p, const osg::Vec3d& want)
{
    EXPECT_VEC_NEAR(LD::deform(p, f), want, 1e-9);
    EXPECT_VEC_NEAR(LD::transform(p, f), want, 1e-9);
}

std::vector<osg::Vec3d> corners(const osg::BoundingBoxd& b)
{
    std::vector<osg::Vec3d> v;
    for (unsigned i = 0; i < 8; ++i)
        v.push_back(b.corner(i));
    v.push_back(b.center());
    return v;
}
} // namespace

TEST(LandmarkDeformationTest, DefaultsValidate)
{
    osg::ref_ptr<LD> d = new LD;
    EXPECT_EQ(d->validate(), "");
    EXPECT_TRUE(d->getScalingEnabled() && d->getRotationEnabled() && d->getFlatteningEnabled() &&
                d->getBillboardEnabled());
    EXPECT_FALSE(d->getSinkingEnabled());
    EXPECT_EQ(d->getDriverKind(), SaliencyMetric::VIEW_ANGLE);
    EXPECT_EQ(d->getSinkTypes(), LD::FeatureTypes{FeatureType::Building});
}

TEST(LandmarkDeformationTest, Smoothstep)
{
    EXPECT_DOUBLE_EQ(LD::smoothstep(0, 10, -1), 0.0);
    EXPECT_DOUBLE_EQ(LD::smoothstep(0, 10, 5), 0.5);
    EXPECT_DOUBLE_EQ(LD::smoothstep(0, 10, 2.5), 0.15625); // t = 1/4: t²(3 - 2t) = 5/32
    EXPECT_DOUBLE_EQ(LD::smoothstep(0, 10, 11), 1.0);
    EXPECT_DOUBLE_EQ(LD::smoothstep(5, 5, 4.9), 0.0); // equal edges: a step at the edge
    EXPECT_DOUBLE_EQ(LD::smoothstep(5, 5, 5), 1.0);
    EXPECT_DOUBLE_EQ(LD::smoothstep(0, 1, std::nan("")), 0.0);
}

// (a): s = 1 + (maxScale - 1) smoothstep(200, 1000, d) f, about the footprint centre.
TEST(LandmarkDeformationTest, ScalingByViewDistanceAndInterest)
{
    osg::ref_ptr<LD> d = only(true, false, false, false);
    // The eye level with the centre (the driver is irrelevant: no morphing step is on).
    for (const auto& c :
         {std::make_pair(100.0, 1.0), std::make_pair(600.0, 1.5), std::make_pair(1500.0, 2.0)})
    {
        const LD::View view =
            LD::View::lookAt(kCentre + osg::Vec3d(0, c.first, 0), kCentre, osg::Vec3d(0, 0, 1));
        const LD::FeatureFrame f = d->computeFrame(landmark(), view);
        EXPECT_NEAR(f.scale, c.second, 1e-12) << "distance " << c.first;
        // The top corner (110, 220, 30) is (5, 10, 30) from b = (105, 210, 0).
        expectDeformed(f, osg::Vec3d(110, 220, 30),
                       osg::Vec3d(105, 210, 0) + osg::Vec3d(5, 10, 30) * c.second);
        expectDeformed(f, osg::Vec3d(105, 210, 0), osg::Vec3d(105, 210, 0)); // the base stays
    }
    // Interest 0.75 fades by smoothstep(0.6, 0.9, 0.75) = 0.5: s = 1 + 1 · 0.5 · 0.5 at 600.
    const LD::View mid = LD::View::lookAt(kCentre + osg::Vec3d(0, 600, 0), kCentre, osg::Vec3d(0, 0, 1));
    EXPECT_NEAR(d->computeFrame(landmark(osg::Vec3d(), 0.75), mid).scale, 1.25, 1e-12);
    // Interest 0.6 and below: not scaled at all.
    const LD::FeatureFrame low = d->computeFrame(landmark(osg::Vec3d(), 0.5), mid);
    EXPECT_DOUBLE_EQ(low.scale, 1.0);
    EXPECT_TRUE(low.isIdentity());
}

// (b): best view +X turned to face an eye at +Y: 90 degrees counter-clockwise about the
// vertical through c.
TEST(LandmarkDeformationTest, RotationTurnsTheBestViewToTheEye)
{
    osg::ref_ptr<LD> d = only(false, true, false, false);
    const LD::View view = LD::View::lookAt(kCentre + osg::Vec3d(0, 100, 0), kCentre, osg::Vec3d(0, 0, 1));
    const LD::FeatureFrame f = d->computeFrame(landmark(osg::Vec3d(1, 0, 0)), view);
    EXPECT_DOUBLE_EQ(f.morph, 1.0);
    EXPECT_VEC_NEAR(f.facing, osg::Vec3d(0, 1, 0), 1e-12);
    EXPECT_NEAR(f.rotation, kPi / 2, 1e-12);
    // The centre of the +X face, (110, 210, 15), goes to the +Y side: (105, 215, 15).
    expectDeformed(f, osg::Vec3d(110, 210, 15), osg::Vec3d(105, 215, 15));
    // (110, 220, 30): (5, 10) from the axis turns to (-10, 5).
    expectDeformed(f, osg::Vec3d(110, 220, 30), osg::Vec3d(95, 215, 30));
    // An eye at -X: best view +X turns by 180 degrees.
    const LD::View west = LD::View::lookAt(kCentre + osg::Vec3d(-100, 0, 0), kCentre, osg::Vec3d(0, 0, 1));
    EXPECT_NEAR(std::fabs(d->computeFrame(landmark(osg::Vec3d(1, 0, 0)), west).rotation), kPi, 1e-12);
    // A best view that already faces the eye: no rotation.
    EXPECT_NEAR(d->computeFrame(landmark(osg::Vec3d(0, 1, 0)), view).rotation, 0.0, 1e-12);
    // A best view with a vertical part counts by its horizontal part.
    EXPECT_NEAR(d->computeFrame(landmark(osg::Vec3d(0.6, 0, 0.8)), view).rotation, kPi / 2, 1e-12);
}

// (c): projection onto the vertical plane through c facing the eye (y = 210 for an eye at +Y).
TEST(LandmarkDeformationTest, FlatteningProjectsOntoThePlane)
{
    osg::ref_ptr<LD> d = only(false, false, true, false);
    const LD::View view = LD::View::lookAt(kCentre + osg::Vec3d(0, 100, 0), kCentre, osg::Vec3d(0, 0, 1));
    const LD::FeatureFrame f = d->computeFrame(landmark(), view);
    expectDeformed(f, osg::Vec3d(110, 220, 30), osg::Vec3d(110, 210, 30));
    expectDeformed(f, osg::Vec3d(100, 200, 0), osg::Vec3d(100, 210, 0));
    // With the rotation: (95, 215, 30) flattened to (95, 210, 30).
    osg::ref_ptr<LD> both = only(false, true, true, false);
    expectDeformed(both->computeFrame(landmark(osg::Vec3d(1, 0, 0)), view), osg::Vec3d(110, 220, 30),
                   osg::Vec3d(95, 210, 30));
    // An eye at +X+Y (45 degrees): the plane through c with normal (1, 1, 0)/sqrt 2; the
    // corner (110, 220, 30) is (5, 10) off c, 15/sqrt 2 along the normal: it moves by
    // -(7.5, 7.5) to (102.5, 212.5, 30).
    const LD::View diagonal =
        LD::View::lookAt(kCentre + osg::Vec3d(100, 100, 0), kCentre, osg::Vec3d(0, 0, 1));
    expectDeformed(d->computeFrame(landmark(), diagonal), osg::Vec3d(110, 220, 30),
                   osg::Vec3d(102.5, 212.5, 30));
}

// (d): the flattened landmark tilted about the horizontal axis through b by the elevation.
TEST(LandmarkDeformationTest, BillboardTiltsByTheCameraElevation)
{
    osg::ref_ptr<LD> d = only(false, false, true, true);
    const double e = 30.0 * kPi / 180.0;
    const LD::View view = LD::View::lookAt(kCentre + osg::Vec3d(0, 100 * std::cos(e), 100 * std::sin(e)),
                                           kCentre, osg::Vec3d(0, 0, 1));
    const LD::FeatureFrame f = d->computeFrame(landmark(), view);
    EXPECT_NEAR(f.tilt, e, 1e-12);
    // On the plane y = 210 a point at height z tips away from the eye: (x, 210 - z sin 30,
    // z cos 30). The top of the +X edge, (110, 210, 30), goes to (110, 195, 25.98).
    expectDeformed(f, osg::Vec3d(110, 210, 30), osg::Vec3d(110, 210 - 15, 30 * std::cos(e)));
    expectDeformed(f, osg::Vec3d(110, 220, 30), osg::Vec3d(110, 195, 30 * std::cos(e)));
    expectDeformed(f, osg::Vec3d(100, 200, 0), osg::Vec3d(100, 210, 0)); // the foot stays
    // The plane's normal is now the direction to the eye: the deformed face is perpendicular
    // to the view. Normals map through the cofactor matrix.
    osg::Vec3d n = osg::Vec3d(0, 1, 0) * f.normalMatrix;
    n.normalize();
    EXPECT_VEC_NEAR(n, osg::Vec3d(0, std::cos(e), std::sin(e)), 1e-12);
    // Every normal with a part along the facing maps onto the plane's normal.
    osg::Vec3d m = osg::Vec3d(0.3, 0.5, -0.2) * f.normalMatrix;
    m.normalize();
    EXPECT_VEC_NEAR(m, osg::Vec3d(0, std::cos(e), std::sin(e)), 1e-12);
    EXPECT_VEC_NEAR(LD::deformNormal(osg::Vec3d(0.3, 0.5, -0.2), f), osg::Vec3d(0, std::cos(e), std::sin(e)),
                    1e-12);
    // A side wall (normal along the plane) collapses to a line: its normal keeps its direction.
    EXPECT_VEC_NEAR(LD::deformNormal(osg::Vec3d(2, 0, 0), f), osg::Vec3d(1, 0, 0), 1e-12);
    // The maximum tilt clamps it.
    d->setMaxTiltDegrees(20.0);
    EXPECT_NEAR(d->computeFrame(landmark(), view).tilt, 20.0 * kPi / 180.0, 1e-12);
    // Seen from below: no tilt.
    const LD::View below = LD::View::lookAt(kCentre + osg::Vec3d(0, 100, -50), kCentre, osg::Vec3d(0, 0, 1));
    EXPECT_DOUBLE_EQ(d->computeFrame(landmark(), below).tilt, 0.0);
}

// The four steps at once, blended by the morph amount: mix(S p, T F R S p, a).
TEST(LandmarkDeformationTest, BlendAmountMixesOriginalAndTransformed)
{
    osg::ref_ptr<LD> d = only(false, true, false, false);
    // Driver: view distance 0..200; the eye 100 m away gives interest 0.5, map-likeness 0.5.
    d->setDriverFar(200.0);
    const LD::View view = LD::View::lookAt(kCentre + osg::Vec3d(0, 100, 0), kCentre, osg::Vec3d(0, 0, 1));
    const LD::FeatureFrame half = d->computeFrame(landmark(osg::Vec3d(1, 0, 0)), view);
    EXPECT_NEAR(half.morph, 0.5, 1e-12);
    // Halfway between (110, 220, 30) and its rotated image (95, 215, 30).
    expectDeformed(half, osg::Vec3d(110, 220, 30), osg::Vec3d(102.5, 217.5, 30));
    // Amount 0 (eye within the driver's near) and 1 (beyond its far).
    d->setDriverNear(150.0);
    const LD::FeatureFrame none = d->computeFrame(landmark(osg::Vec3d(1, 0, 0)), view);
    EXPECT_DOUBLE_EQ(none.morph, 0.0);
    EXPECT_TRUE(none.isIdentity());
    expectDeformed(none, osg::Vec3d(110, 220, 30), osg::Vec3d(110, 220, 30));
    d->setDriverNear(0.0);
    d->setDriverFar(50.0);
    expectDeformed(d->computeFrame(landmark(osg::Vec3d(1, 0, 0)), view), osg::Vec3d(110, 220, 30),
                   osg::Vec3d(95, 215, 30));
    // The static interest fades the morph too: 0.75 gives half of it.
    EXPECT_NEAR(d->computeFrame(landmark(osg::Vec3d(1, 0, 0), 0.75), view).morph, 0.5, 1e-12);

    // The default driver: vertical view angle 25..60 degrees. At 45 degrees the ramp's
    // interest is 1 - 20/35, so the map-likeness is 20/35.
    osg::ref_ptr<LD> def = new LD;
    const double e = 45.0 * kPi / 180.0;
    const LD::View oblique = LD::View::lookAt(kCentre + osg::Vec3d(0, 100 * std::cos(e), 100 * std::sin(e)),
                                              kCentre, osg::Vec3d(0, 0, 1));
    EXPECT_NEAR(def->computeFrame(landmark(osg::Vec3d(1, 0, 0)), oblique).morph, 20.0 / 35.0, 1e-9);
}

// The full composition at a few views: the matrix equals the steps everywhere on the box.
TEST(LandmarkDeformationTest, MatrixEqualsTheSteps)
{
    osg::ref_ptr<LD> d = new LD;
    d->setScaleNear(50.0);
    d->setScaleFar(400.0);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int k = 0; k < 40; ++k)
    {
        const double az = u(rng) * 2 * kPi, el = u(rng) * 0.5 * kPi, dist = 20 + u(rng) * 800;
        const osg::Vec3d eye =
            kCentre +
            osg::Vec3d(std::cos(az) * std::cos(el), std::sin(az) * std::cos(el), std::sin(el)) * dist;
        const osg::Vec3d look = kCentre + osg::Vec3d(u(rng) - 0.5, u(rng) - 0.5, 0.0) * 40.0;
        const LD::View view = LD::View::lookAt(eye, look, osg::Vec3d(0, 0, 1));
        const osg::Vec3d best(std::cos(u(rng) * 6.3), std::sin(u(rng) * 6.3), 0.0);
        const LD::FeatureFrame f = d->computeFrame(landmark(best, 0.6 + 0.4 * u(rng)), view);
        ASSERT_TRUE(finite(f.matrix));
        for (const osg::Vec3d& p : corners(kBox))
            EXPECT_VEC_NEAR(LD::transform(p, f), LD::deform(p, f), 1e-9);
    }
}

// Straight down: the horizontal view direction is undefined; the camera's up vector takes
// its place (the limit of the view direction's horizontal part for a camera without roll).
TEST(LandmarkDeformationTest, StraightDownCameraUsesTheUpVector)
{
    osg::ref_ptr<LD> d = only(false, true, true, true);
    const LD::View down(kCentre + osg::Vec3d(0, 0, 500), osg::Vec3d(0, 0, -1), osg::Vec3d(0, 1, 0));
    const LD::FeatureFrame f = d->computeFrame(landmark(osg::Vec3d(1, 0, 0)), down);
    EXPECT_VEC_NEAR(f.facing, osg::Vec3d(0, -1, 0), 1e-12); // facing the screen's bottom
    EXPECT_NEAR(f.rotation, -kPi / 2, 1e-12);
    EXPECT_NEAR(f.tilt, kPi / 2, 1e-12);
    ASSERT_TRUE(finite(f.matrix));
    // (110, 210, 15), the +X face's centre: the rotation by -90 degrees takes (5, 0) to (0, -5):
    // (105, 205, 15); flattened onto y = 210: (105, 210, 15); tilted 90 degrees about the axis
    // through b, its height 15 turns into 15 along the screen's up (+Y): (105, 225, 0).
    expectDeformed(f, osg::Vec3d(110, 210, 15), osg::Vec3d(105, 225, 0));
    // The landmark's top points up the screen: (x, 210, 30) goes to (x', 240, 0).
    EXPECT_NEAR(LD::deform(osg::Vec3d(105, 220, 30), f).y(), 240.0, 1e-9);

    // A camera pitched nearly straight down (no roll) gives the same orientation: no jump.
    const LD::View almost =
        LD::View::lookAt(kCentre + osg::Vec3d(0, -1e-3, 500), kCentre, osg::Vec3d(0, 1, 0));
    const LD::FeatureFrame g = d->computeFrame(landmark(osg::Vec3d(1, 0, 0)), almost);
    EXPECT_VEC_NEAR(g.facing, f.facing, 1e-12);
    for (const osg::Vec3d& p : corners(kBox))
        EXPECT_VEC_NEAR(LD::transform(p, g), LD::transform(p, f), 1e-3);

    // No camera direction given and the eye exactly above the centre, no up vector: the
    // landmark keeps its orientation (faces its best view, no rotation)...
    const LD::View bare(kCentre + osg::Vec3d(0, 0, 500), osg::Vec3d(), osg::Vec3d());
    const LD::FeatureFrame h = d->computeFrame(landmark(osg::Vec3d(1, 0, 0)), bare);
    EXPECT_VEC_NEAR(h.facing, osg::Vec3d(1, 0, 0), 1e-12);
    EXPECT_DOUBLE_EQ(h.rotation, 0.0);
    EXPECT_TRUE(finite(h.matrix));
    // ... and without a best view faces -Y.
    const LD::FeatureFrame k = d->computeFrame(landmark(), bare);
    EXPECT_VEC_NEAR(k.facing, osg::Vec3d(0, -1, 0), 1e-12);
    EXPECT_TRUE(finite(k.matrix));
    for (const osg::Vec3d& p : corners(kBox))
        EXPECT_TRUE(finite(LD::transform(p, k)));
}

TEST(LandmarkDeformationTest, NoBestViewSkipsTheRotation)
{
    osg::ref_ptr<LD> d = only(false, true, true, false);
    const LD::View view = LD::View::lookAt(kCentre + osg::Vec3d(0, 100, 0), kCentre, osg::Vec3d(0, 0, 1));
    for (const osg::Vec3d& none : {osg::Vec3d(), osg::Vec3d(0, 0, 1)}) // zero, or straight up
    {
        const LD::FeatureFrame f = d->computeFrame(landmark(none), view);
        EXPECT_DOUBLE_EQ(f.rotation, 0.0);
        expectDeformed(f, osg::Vec3d(110, 220, 30), osg::Vec3d(110, 210, 30)); // flattened only
    }
}

TEST(LandmarkDeformationTest, DegenerateBoxesStayFinite)
{
    osg::ref_ptr<LD> d = new LD;
    d->setScaleNear(0.0);
    d->setScaleFar(10.0);
    const LD::View views[] = {
        LD::View::lookAt(osg::Vec3d(0, -300, 300), osg::Vec3d(5, 5, 5), osg::Vec3d(0, 0, 1)),
        LD::View(osg::Vec3d(5, 5, 300), osg::Vec3d(0, 0, -1), osg::Vec3d(0, 1, 0)),
        LD::View(osg::Vec3d(5, 5, 5), osg::Vec3d(), osg::Vec3d())};            // the eye at the centre
    const osg::BoundingBoxd boxes[] = {osg::BoundingBoxd(5, 5, 5, 5, 5, 5),    // a point
                                       osg::BoundingBoxd(0, 0, 5, 10, 10, 5),  // zero height
                                       osg::BoundingBoxd(5, 0, 0, 5, 10, 10),  // zero width
                                       osg::BoundingBoxd(0, 5, 0, 10, 5, 10)}; // zero depth
    for (const LD::View& v : views)
        for (const osg::BoundingBoxd& b : boxes)
            for (const osg::Vec3d& best : {osg::Vec3d(), osg::Vec3d(1, 0, 0)})
            {
                const LD::FeatureFrame f = d->computeFrame(landmark(best, 1.0, b), v);
                EXPECT_TRUE(finite(f.matrix));
                EXPECT_TRUE(finite(f.normalMatrix));
                for (const osg::Vec3d& p : corners(b))
                {
                    EXPECT_TRUE(finite(LD::transform(p, f)));
                    EXPECT_VEC_NEAR(LD::transform(p, f), LD::deform(p, f), 1e-9);
                }
            }
    // An empty box: the identity.
    EXPECT_TRUE(
        d->computeFrame(landmark(osg::Vec3d(1, 0, 0), 1.0, osg::BoundingBoxd()), views[0]).isIdentity());
    // A non-finite eye: the identity, never NaN.
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const LD::FeatureFrame f = d->computeFrame(landmark(osg::Vec3d(1, 0, 0)),
                                               LD::View(osg::Vec3d(nan, 0, 0), osg::Vec3d(), osg::Vec3d()));
    EXPECT_TRUE(finite(f.matrix));
    EXPECT_TRUE(finite(f.normalMatrix));
}

// Non-landmarks of the sink types shrink towards b and sink by their height, by the
// map-likeness; landmarks, other types, and the default (off) leave them alone.
TEST(LandmarkDeformationTest, NonLandmarksShrinkAndSink)
{
    osg::ref_ptr<LD> d = only(true, true, true, true);
    LD::FeatureInput building = landmark();
    building.landmark = false;
    const LD::View view = LD::View::lookAt(kCentre + osg::Vec3d(0, 300, 300), kCentre, osg::Vec3d(0, 0, 1));
    EXPECT_TRUE(d->computeFrame(building, view).isIdentity()) << "sinking is off by default";
    d->setSinkingEnabled(true);
    const LD::FeatureFrame f = d->computeFrame(building, view);
    EXPECT_DOUBLE_EQ(f.sink, 1.0);
    // b + 0.5 (5, 10, 30) - (0, 0, 30) = (107.5, 215, -15): the top half a height underground.
    expectDeformed(f, osg::Vec3d(110, 220, 30), osg::Vec3d(107.5, 215, -15));
    expectDeformed(f, osg::Vec3d(100, 200, 0), osg::Vec3d(102.5, 205, -30));
    // Half the amount: driver 0..848.5 at distance 424.26 (the eye is 300 sqrt 2 away).
    d->setDriverFar(2.0 * 300.0 * std::sqrt(2.0));
    const LD::FeatureFrame half = d->computeFrame(building, view);
    EXPECT_NEAR(half.sink, 0.5, 1e-12);
    expectDeformed(half, osg::Vec3d(110, 220, 30),
                   osg::Vec3d(105, 210, 0) + osg::Vec3d(5, 10, 30) * 0.75 - osg::Vec3d(0, 0, 15));
    building.type = FeatureType::Street;
    EXPECT_TRUE(d->computeFrame(building, view).isIdentity()) << "streets are not a sink type";
    d->setSinkTypes({FeatureType::Street});
    EXPECT_FALSE(d->computeFrame(building, view).isIdentity());
}

// With sinkFollowsMapStyles the amount is the feature's weight of map-like configurations
// (FeatureInput::mapWeight, clamped to [0, 1]), not the driver's map-likeness (which is 1 here);
// unknown (negative) falls back to the driver; landmarks keep the driver for their morph.
TEST(LandmarkDeformationTest, SinkingCanFollowTheScenariosMapWeight)
{
    osg::ref_ptr<LD> d = only(true, true, true, true);
    d->setSinkingEnabled(true);
    d->setSinkFollowsMapStyles(true);
    LD::FeatureInput building = landmark();
    building.landmark = false;
    const LD::View view = LD::View::lookAt(kCentre + osg::Vec3d(0, 300, 300), kCentre, osg::Vec3d(0, 0, 1));
    building.mapWeight = 0.25;
    LD::FeatureFrame f = d->computeFrame(building, view);
    EXPECT_DOUBLE_EQ(f.mapLikeness, 1.0);
    EXPECT_DOUBLE_EQ(f.sink, 0.25);
    // b + (1 - 0.25 x 0.5) (5, 10, 30) - (0, 0, 0.25 x 30).
    expectDeformed(f, osg::Vec3d(110, 220, 30),
                   osg::Vec3d(105, 210, 0) + osg::Vec3d(5, 10, 30) * 0.875 - osg::Vec3d(0, 0, 7.5));
    building.mapWeight = 0.0;
    EXPECT_TRUE(d->computeFrame(building, view).isIdentity()) << "drawn in detail: stays";
    building.mapWeight = 3.0;
    EXPECT_DOUBLE_EQ(d->computeFrame(building, view).sink, 1.0);
    building.mapWeight = -1.0;
    EXPECT_DOUBLE_EQ(d->computeFrame(building, view).sink, 1.0) << "unknown: the driver";
    LD::FeatureInput mark = landmark();
    mark.mapWeight = 0.0;
    EXPECT_GT(d->computeFrame(mark, view).morph, 0.0) << "landmarks keep the driver";
    // The map styles.
    EXPECT_TRUE(d->isMapStyle("streets"));
    EXPECT_FALSE(d->isMapStyle("photorealistic"));
    d->setMapStyles({"blueprint"});
    EXPECT_TRUE(d->isMapStyle("blueprint"));
    EXPECT_FALSE(d->isMapStyle("cartographic"));
}

TEST(LandmarkDeformationTest, ValidationNamesTheProblem)
{
    auto problem = [](void (*change)(LD&))
    {
        osg::ref_ptr<LD> d = new LD;
        change(*d);
        return d->validate();
    };
    EXPECT_NE(problem([](LD& d) { d.setScaleNear(2000.0); }).find("scale distances"), std::string::npos);
    EXPECT_NE(problem([](LD& d) { d.setMaxScale(0.0); }).find("maximum scale"), std::string::npos);
    EXPECT_NE(problem([](LD& d) { d.setInterestFadeEnd(1.5); }).find("interest fade"), std::string::npos);
    EXPECT_NE(problem([](LD& d) { d.setDriverKind(SaliencyMetric::REGION); }).find("driver"),
              std::string::npos);
    EXPECT_NE(problem([](LD& d) { d.setDriverFar(-1.0); }).find("driver"), std::string::npos);
    EXPECT_NE(problem([](LD& d) { d.setMaxTiltDegrees(95.0); }).find("tilt"), std::string::npos);
    EXPECT_NE(problem([](LD& d) { d.setShrinkFactor(2.0); }).find("shrink"), std::string::npos);
    EXPECT_NE(problem([](LD& d) { d.setSinkFactor(std::nan("")); }).find("sink factor"), std::string::npos);
    // A scenario reports it as an error.
    osg::ref_ptr<UsageScenario> s = ScenarioLibrary::createBuiltin("view-angle");
    ASSERT_NE(s->getLandmarkDeformation(), nullptr);
    EXPECT_TRUE(s->validate().ok());
    s->getLandmarkDeformation()->setMaxScale(-1.0);
    const UsageScenario::Validation v = s->validate();
    ASSERT_FALSE(v.ok());
    bool named = false;
    for (const std::string& e : v.errors)
        named = named || e.find("landmark deformation: maximum scale") != std::string::npos;
    EXPECT_TRUE(named);
}

// Uniforms: created on the first call, then only set (the same objects every frame).
TEST(LandmarkDeformationTest, UniformsAreCreatedOnceThenSet)
{
    osg::ref_ptr<osg::StateSet> node = new osg::StateSet, feature = new osg::StateSet;
    LD::applyScenario(*node, nullptr);
    bool enabled = true;
    ASSERT_NE(node->getUniform("loa_deformEnabled"), nullptr);
    node->getUniform("loa_deformEnabled")->get(enabled);
    EXPECT_FALSE(enabled);
    osg::ref_ptr<LD> d = new LD;
    LD::applyScenario(*node, d.get());
    node->getUniform("loa_deformEnabled")->get(enabled);
    EXPECT_TRUE(enabled);
    osg::Matrixf m;
    node->getUniform("loa_deformMatrix")->get(m);
    EXPECT_TRUE(m.isIdentity());

    const LD::View view = LD::View::lookAt(kCentre + osg::Vec3d(0, 600, 600), kCentre, osg::Vec3d(0, 0, 1));
    d->applyFeature(*feature, landmark(osg::Vec3d(1, 0, 0)), view);
    const osg::Uniform* matrix = feature->getUniform("loa_deformMatrix");
    const osg::Uniform* normal = feature->getUniform("loa_deformNormalMatrix");
    ASSERT_NE(matrix, nullptr);
    ASSERT_NE(normal, nullptr);
    EXPECT_EQ(matrix->getType(), osg::Uniform::FLOAT_MAT4);
    EXPECT_EQ(normal->getType(), osg::Uniform::FLOAT_MAT3);
    const LD::FeatureFrame f = d->computeFrame(landmark(osg::Vec3d(1, 0, 0)), view);
    matrix->get(m);
    EXPECT_TRUE(m == osg::Matrixf(f.matrix));
    EXPECT_FALSE(m.isIdentity());
    const unsigned uniforms = unsigned(feature->getUniformList().size());
    d->applyFeature(*feature, landmark(),
                    LD::View::lookAt(kCentre + osg::Vec3d(0, 50, 0), kCentre, osg::Vec3d(0, 0, 1)));
    EXPECT_EQ(feature->getUniform("loa_deformMatrix"), matrix);
    EXPECT_EQ(feature->getUniform("loa_deformNormalMatrix"), normal);
    EXPECT_EQ(feature->getUniformList().size(), uniforms);
}

TEST(LandmarkDeformationTest, ViewFromViewToScene)
{
    osg::Matrixd view;
    view.makeLookAt(osg::Vec3d(10, -100, 50), osg::Vec3d(10, 0, 0), osg::Vec3d(0, 0, 1));
    const LD::View v = LD::View::fromViewToScene(osg::Matrixd::inverse(view));
    const LD::View w = LD::View::lookAt(osg::Vec3d(10, -100, 50), osg::Vec3d(10, 0, 0), osg::Vec3d(0, 0, 1));
    EXPECT_VEC_NEAR(v.eye, w.eye, 1e-9);
    EXPECT_VEC_NEAR(v.forward, w.forward, 1e-12);
    EXPECT_VEC_NEAR(v.up, w.up, 1e-12);
}

// ---- serialization ----------------------------------------------------------------------------

namespace
{
std::string fileBytes(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

template <class T>
osg::ref_ptr<T> roundTrip(const T& obj, const std::string& dir, const std::string& name,
                          const std::string& ext)
{
    const std::string first = dir + "/" + name + "-first." + ext,
                      second = dir + "/" + name + "-second." + ext;
    EXPECT_TRUE(osgDB::writeObjectFile(obj, first)) << first;
    osg::ref_ptr<osg::Object> read = osgDB::readRefObjectFile(first);
    osg::ref_ptr<T> back = dynamic_cast<T*>(read.get());
    EXPECT_TRUE(back.valid()) << first;
    if (!back) return back;
    EXPECT_TRUE(osgDB::writeObjectFile(*back, second)) << second;
    EXPECT_FALSE(fileBytes(first).empty());
    EXPECT_TRUE(fileBytes(first) == fileBytes(second)) << name << "." << ext << "\n" << fileBytes(first);
    return back;
}

osg::ref_ptr<LD> everyFieldChanged()
{
    osg::ref_ptr<LD> d = new LD;
    d->setName("map landmarks");
    d->setScalingEnabled(false);
    d->setRotationEnabled(false);
    d->setFlatteningEnabled(false);
    d->setBillboardEnabled(false);
    d->setSinkingEnabled(true);
    d->setScaleNear(125.5);
    d->setScaleFar(1500.25);
    d->setMaxScale(3.5);
    d->setInterestFadeBegin(0.25);
    d->setInterestFadeEnd(0.75);
    d->setDriverKind(SaliencyMetric::VIEW_DISTANCE);
    d->setDriverNear(150.5);
    d->setDriverFar(900.125);
    d->setMaxTiltDegrees(72.5);
    d->setSinkTypes({FeatureType::Building, FeatureType::Generic, FeatureType::Green});
    d->setShrinkFactor(0.375);
    d->setSinkFactor(1.25);
    d->setSinkFollowsMapStyles(true);
    d->setMapStyles({"cartographic", "my \"map\" style"});
    return d;
}

void expectSame(const LD& a, const LD& b)
{
    EXPECT_EQ(a.getName(), b.getName());
    EXPECT_EQ(a.getScalingEnabled(), b.getScalingEnabled());
    EXPECT_EQ(a.getRotationEnabled(), b.getRotationEnabled());
    EXPECT_EQ(a.getFlatteningEnabled(), b.getFlatteningEnabled());
    EXPECT_EQ(a.getBillboardEnabled(), b.getBillboardEnabled());
    EXPECT_EQ(a.getSinkingEnabled(), b.getSinkingEnabled());
    EXPECT_DOUBLE_EQ(a.getScaleNear(), b.getScaleNear());
    EXPECT_DOUBLE_EQ(a.getScaleFar(), b.getScaleFar());
    EXPECT_DOUBLE_EQ(a.getMaxScale(), b.getMaxScale());
    EXPECT_DOUBLE_EQ(a.getInterestFadeBegin(), b.getInterestFadeBegin());
    EXPECT_DOUBLE_EQ(a.getInterestFadeEnd(), b.getInterestFadeEnd());
    EXPECT_EQ(a.getDriverKind(), b.getDriverKind());
    EXPECT_DOUBLE_EQ(a.getDriverNear(), b.getDriverNear());
    EXPECT_DOUBLE_EQ(a.getDriverFar(), b.getDriverFar());
    EXPECT_DOUBLE_EQ(a.getMaxTiltDegrees(), b.getMaxTiltDegrees());
    EXPECT_EQ(a.getSinkTypes(), b.getSinkTypes());
    EXPECT_DOUBLE_EQ(a.getShrinkFactor(), b.getShrinkFactor());
    EXPECT_DOUBLE_EQ(a.getSinkFactor(), b.getSinkFactor());
    EXPECT_EQ(a.getSinkFollowsMapStyles(), b.getSinkFollowsMapStyles());
    EXPECT_EQ(a.getMapStyles(), b.getMapStyles());
}
} // namespace

TEST(LandmarkDeformationTest, SerializerRoundTrips)
{
    const std::string dir = loatest::freshDirectory("LandmarkDeformationTest/roundtrip");
    osg::ref_ptr<LD> changed = everyFieldChanged(), defaults = new LD;
    for (const char* ext : {"osgt", "osgb", "osgx"})
    {
        osg::ref_ptr<LD> back = roundTrip(*changed, dir, "changed", ext);
        if (back) expectSame(*changed, *back);
        back = roundTrip(*defaults, dir, "defaults", ext);
        if (back) expectSame(*defaults, *back);
        // An empty sink-type list is not the default and survives too.
        osg::ref_ptr<LD> empty = new LD;
        empty->setSinkTypes({});
        back = roundTrip(*empty, dir, "empty", ext);
        if (back)
        {
            EXPECT_TRUE(back->getSinkTypes().empty()) << ext;
        }
        // Inside a scenario.
        osg::ref_ptr<UsageScenario> s = ScenarioLibrary::createBuiltin("view-angle");
        s->setLandmarkDeformation(changed.get());
        osg::ref_ptr<UsageScenario> sb = roundTrip(*s, dir, "scenario", ext);
        if (sb)
        {
            ASSERT_NE(sb->getLandmarkDeformation(), nullptr) << ext;
            expectSame(*changed, *sb->getLandmarkDeformation());
        }
    }
    // The text names the fields.
    const std::string text = fileBytes(dir + "/changed-first.osgt");
    for (const char* field :
         {"ScalingEnabled FALSE", "SinkingEnabled TRUE", "DriverKind VIEW_DISTANCE", "MaxTiltDegrees 72.5",
          "SinkTypes 3", "generic", "SinkFactor 1.25", "SinkFollowsMapStyles TRUE", "MapStyles 2"})
        EXPECT_NE(text.find(field), std::string::npos) << field << "\n" << text;
}

TEST(LandmarkDeformationTest, ScenarioFilesWithoutItReadAsNone)
{
    // A library file written before the deformation existed (no such property).
    osg::ref_ptr<UsageScenario> s =
        ScenarioLibrary::readFile(std::string(LOA_SOURCE_DIR) + "/data/scenarios/distance.osgt");
    EXPECT_EQ(s->getLandmarkDeformation(), nullptr);
    osg::ref_ptr<UsageScenario> v =
        ScenarioLibrary::readFile(std::string(LOA_SOURCE_DIR) + "/data/scenarios/view-angle.osgt");
    ASSERT_NE(v->getLandmarkDeformation(), nullptr);
    // The defaults, with sinking by the map styles' weight (issue 19).
    osg::ref_ptr<LD> expected = new LD;
    expected->setSinkingEnabled(true);
    expected->setSinkFollowsMapStyles(true);
    expectSame(*v->getLandmarkDeformation(), *expected);
    // The copy constructor copies it (deep copies are their own objects).
    osg::ref_ptr<UsageScenario> copy = osg::clone(v.get(), osg::CopyOp::DEEP_COPY_ALL);
    ASSERT_NE(copy->getLandmarkDeformation(), nullptr);
    EXPECT_NE(copy->getLandmarkDeformation(), v->getLandmarkDeformation());
}

TEST(LandmarkDeformationTest, UnknownSinkTypeFailsTheRead)
{
    const std::string dir = loatest::freshDirectory("LandmarkDeformationTest/bad");
    osg::ref_ptr<LD> d = new LD;
    d->setSinkTypes({FeatureType::Green});
    ASSERT_TRUE(osgDB::writeObjectFile(*d, dir + "/good.osgt"));
    std::string text = fileBytes(dir + "/good.osgt");
    const std::size_t at = text.find("green");
    ASSERT_NE(at, std::string::npos);
    text.replace(at, 5, "lava");
    std::ofstream(dir + "/bad.osgt") << text;
    osg::ref_ptr<osg::Object> read = osgDB::readRefObjectFile(dir + "/bad.osgt");
    EXPECT_FALSE(read.valid());
}
