// SaliencyMetric (paper 004 §3.2.1, Figure 5) and RegionOfInterest: each kind's quantity at
// hand-computed points, the near/far ramp, bounds over boxes against random sampling, and
// validation. Expected numbers are worked out in the comment beside them.
#include <osgLoA/interest/RegionOfInterest>
#include <osgLoA/interest/SaliencyMetric>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

using namespace osgLoA;

namespace
{
typedef SaliencyMetric M;
const double kInf = std::numeric_limits<double>::infinity();

/** Temporaries of osg::Referenced types (protected destructors) live in a ref_ptr. */
template <typename... A> osg::ref_ptr<SaliencyMetric> mk(A... a)
{
    return new SaliencyMetric(a...);
}
osg::ref_ptr<RegionOfInterest> mr()
{
    return new RegionOfInterest;
}
osg::ref_ptr<RegionOfInterest> mr(RegionOfInterest::Shape shape, const RegionOfInterest::Vertices& v,
                                  double radius = 0.0)
{
    return new RegionOfInterest(shape, v, radius);
}

SaliencyView viewFrom(const osg::Vec3d& eye)
{
    SaliencyView v;
    v.eye = eye;
    return v;
}

double measure(M::Kind kind, const osg::Vec3d& p, const SaliencyView& view, double featureInterest = 0.0)
{
    osg::ref_ptr<M> m = new M(kind, 0.0, 1.0);
    return m->measure(p, view, featureInterest);
}
} // namespace

TEST(SaliencyMetricTest, ViewDistanceOnPythagoreanTriangles)
{
    const SaliencyView v = viewFrom(osg::Vec3d(0, 0, 0));
    EXPECT_DOUBLE_EQ(measure(M::VIEW_DISTANCE, osg::Vec3d(3, 4, 0), v), 5.0);   // 3-4-5
    EXPECT_DOUBLE_EQ(measure(M::VIEW_DISTANCE, osg::Vec3d(0, -3, 4), v), 5.0);  // 3-4-5 in y/z
    EXPECT_DOUBLE_EQ(measure(M::VIEW_DISTANCE, osg::Vec3d(5, 0, 12), v), 13.0); // 5-12-13
    EXPECT_DOUBLE_EQ(measure(M::VIEW_DISTANCE, osg::Vec3d(2, 3, 6), v), 7.0);   // 4 + 9 + 36 = 49
    // Eye away from the origin: (1,2,3) to (4,6,3) is (3,4,0) -> 5.
    EXPECT_DOUBLE_EQ(measure(M::VIEW_DISTANCE, osg::Vec3d(4, 6, 3), viewFrom(osg::Vec3d(1, 2, 3))), 5.0);
    EXPECT_DOUBLE_EQ(measure(M::VIEW_DISTANCE, osg::Vec3d(1, 2, 3), viewFrom(osg::Vec3d(1, 2, 3))), 0.0);
}

TEST(SaliencyMetricTest, VerticalViewAngle)
{
    const SaliencyView v = viewFrom(osg::Vec3d(0, 0, 100));
    // Height difference 100 over horizontal distance 100: atan(1) = 45 degrees.
    EXPECT_NEAR(measure(M::VIEW_ANGLE, osg::Vec3d(100, 0, 0), v), 45.0, 1e-12);
    EXPECT_NEAR(measure(M::VIEW_ANGLE, osg::Vec3d(60, -80, 0), v), 45.0, 1e-12); // horizontal 3-4-5: 100
    // Straight down: a bird's-eye view, 90 degrees.
    EXPECT_NEAR(measure(M::VIEW_ANGLE, osg::Vec3d(0, 0, 0), v), 90.0, 1e-12);
    // tan(30°) = 1/sqrt(3): horizontal 100·sqrt(3) -> 30 degrees; tan(60°) = sqrt(3).
    EXPECT_NEAR(measure(M::VIEW_ANGLE, osg::Vec3d(100.0 * std::sqrt(3.0), 0, 0), v), 30.0, 1e-12);
    EXPECT_NEAR(measure(M::VIEW_ANGLE, osg::Vec3d(0, 100.0 / std::sqrt(3.0), 0), v), 60.0, 1e-12);
    // Level with or above the eye: 0.
    EXPECT_EQ(measure(M::VIEW_ANGLE, osg::Vec3d(100, 0, 100), v), 0.0);
    EXPECT_EQ(measure(M::VIEW_ANGLE, osg::Vec3d(50, 0, 150), v), 0.0);
    EXPECT_EQ(measure(M::VIEW_ANGLE, osg::Vec3d(0, 0, 150), v), 0.0); // straight up
    EXPECT_EQ(measure(M::VIEW_ANGLE, osg::Vec3d(0, 0, 100), v), 0.0); // the eye itself
}

TEST(SaliencyMetricTest, RegionDistanceToCirclesPolylinesAndPolygons)
{
    std::vector<osg::ref_ptr<RegionOfInterest>> regions;
    SaliencyView v = viewFrom(osg::Vec3d(0, 0, 500));
    v.regions = &regions;
    // No region: +infinity, interest 0.
    EXPECT_EQ(measure(M::REGION, osg::Vec3d(1, 2, 3), v), kInf);
    EXPECT_EQ(mk(M::REGION, 0.0, 100.0)->evaluate(osg::Vec3d(1, 2, 3), v, 0.0), 0.0);

    // A circle of radius 10 around (0,0): (30,40) is 50 from the centre -> 40 from the disc;
    // the point's height does not count (ground projection).
    regions.push_back(new RegionOfInterest(RegionOfInterest::CIRCLES, {{0.0, 0.0}}, 10.0));
    EXPECT_DOUBLE_EQ(measure(M::REGION, osg::Vec3d(30, 40, 0), v), 40.0);
    EXPECT_DOUBLE_EQ(measure(M::REGION, osg::Vec3d(30, 40, 77), v), 40.0);
    EXPECT_EQ(measure(M::REGION, osg::Vec3d(6, 8, 0), v), 0.0); // 10 from the centre: on the rim
    EXPECT_EQ(measure(M::REGION, osg::Vec3d(1, 1, 0), v), 0.0); // inside
    // A second region nearer to the point wins: a route (0,100)-(100,100)-(100,200), radius 0.
    regions.push_back(new RegionOfInterest(RegionOfInterest::POLYLINE, {{0, 100}, {100, 100}, {100, 200}}));
    EXPECT_DOUBLE_EQ(measure(M::REGION, osg::Vec3d(50, 80, 0), v), 20.0);   // below the first segment
    EXPECT_DOUBLE_EQ(measure(M::REGION, osg::Vec3d(130, 150, 0), v), 30.0); // beside the second
    EXPECT_DOUBLE_EQ(measure(M::REGION, osg::Vec3d(-30, 140, 0), v), 50.0); // 3-4-5 from the end (0,100)
    EXPECT_DOUBLE_EQ(measure(M::REGION, osg::Vec3d(130, 240, 0), v), 50.0); // 3-4-5 from the end (100,200)
    EXPECT_DOUBLE_EQ(measure(M::REGION, osg::Vec3d(30, 40, 0), v), 40.0);   // still nearer the circle
    // A null entry is skipped.
    regions.push_back(nullptr);
    EXPECT_DOUBLE_EQ(measure(M::REGION, osg::Vec3d(50, 80, 0), v), 20.0);
}

TEST(SaliencyMetricTest, FocusBoxDistance)
{
    SaliencyView v = viewFrom(osg::Vec3d());
    EXPECT_EQ(measure(M::FOCUS, osg::Vec3d(1, 2, 3), v), kInf); // no focus object
    v.focus = osg::BoundingBoxd(0, 0, 0, 10, 10, 10);
    EXPECT_DOUBLE_EQ(measure(M::FOCUS, osg::Vec3d(13, 14, 5), v), 5.0);   // (3, 4, 0) outside
    EXPECT_DOUBLE_EQ(measure(M::FOCUS, osg::Vec3d(13, 14, 22), v), 13.0); // (3, 4, 12): 9+16+144 = 169
    EXPECT_DOUBLE_EQ(measure(M::FOCUS, osg::Vec3d(-5, 5, 5), v), 5.0);
    EXPECT_EQ(measure(M::FOCUS, osg::Vec3d(5, 5, 5), v), 0.0);  // inside
    EXPECT_EQ(measure(M::FOCUS, osg::Vec3d(10, 0, 3), v), 0.0); // on the boundary
    // A point focus (box of zero size).
    v.focus = osg::BoundingBoxd(1, 1, 1, 1, 1, 1);
    EXPECT_DOUBLE_EQ(measure(M::FOCUS, osg::Vec3d(4, 5, 1), v), 5.0);
}

TEST(SaliencyMetricTest, FeatureInterestIsTheFeaturesOwn)
{
    const SaliencyView v = viewFrom(osg::Vec3d());
    osg::ref_ptr<M> m = new M(M::FEATURE_INTEREST, 0.0, 0.0);
    EXPECT_EQ(m->measure(osg::Vec3d(9, 9, 9), v, 0.625), 0.625);
    EXPECT_EQ(m->evaluate(osg::Vec3d(9, 9, 9), v, 0.625), 0.625); // no ramp
    EXPECT_EQ(m->interest(1.5), 1.0);                             // clamped
    EXPECT_EQ(m->interest(-0.5), 0.0);
    EXPECT_EQ(m->interest(std::nan("")), 0.0);
}

TEST(SaliencyMetricTest, RampValues)
{
    // near 100, far 300: 1 - (q - 100)/200.
    EXPECT_EQ(M::ramp(50.0, 100.0, 300.0), 1.0);
    EXPECT_EQ(M::ramp(100.0, 100.0, 300.0), 1.0);
    EXPECT_DOUBLE_EQ(M::ramp(150.0, 100.0, 300.0), 0.75);   // 1 - 50/200
    EXPECT_DOUBLE_EQ(M::ramp(200.0, 100.0, 300.0), 0.5);    // 1 - 100/200
    EXPECT_NEAR(M::ramp(290.0, 100.0, 300.0), 0.05, 1e-15); // 1 - 190/200
    EXPECT_EQ(M::ramp(300.0, 100.0, 300.0), 0.0);
    EXPECT_EQ(M::ramp(1e9, 100.0, 300.0), 0.0);
    EXPECT_EQ(M::ramp(kInf, 100.0, 300.0), 0.0);
    EXPECT_EQ(M::ramp(std::nan(""), 100.0, 300.0), 0.0);
    // near == far: a step, 1 up to and including near.
    EXPECT_EQ(M::ramp(100.0, 100.0, 100.0), 1.0);
    EXPECT_EQ(M::ramp(std::nextafter(100.0, 200.0), 100.0, 100.0), 0.0);
    EXPECT_EQ(M::ramp(99.0, 100.0, 100.0), 1.0);
    EXPECT_EQ(M::ramp(0.0, 0.0, 0.0), 1.0);
    // The member applies the metric's own near/far: view angle 25..60 at 45 degrees:
    // 1 - 20/35 = 0.428571...
    EXPECT_NEAR(mk(M::VIEW_ANGLE, 25.0, 60.0)->interest(45.0), 1.0 - 20.0 / 35.0, 1e-15);
    // evaluate() = interest(measure()): distance 5 with near 0, far 10 -> 0.5.
    EXPECT_DOUBLE_EQ(
        mk(M::VIEW_DISTANCE, 0.0, 10.0)->evaluate(osg::Vec3d(3, 4, 0), viewFrom(osg::Vec3d()), 0.0), 0.5);
}

namespace
{
osg::BoundingBoxd randomBox(std::mt19937& rng)
{
    std::uniform_real_distribution<double> c(-300.0, 300.0), s(0.0, 120.0);
    const osg::Vec3d lo(c(rng), c(rng), c(rng) * 0.2);
    return osg::BoundingBoxd(lo, lo + osg::Vec3d(s(rng), s(rng), s(rng) * 0.5));
}

osg::Vec3d randomPointIn(const osg::BoundingBoxd& b, std::mt19937& rng)
{
    std::uniform_real_distribution<double> u(0.0, 1.0);
    return osg::Vec3d(b.xMin() + u(rng) * (b.xMax() - b.xMin()), b.yMin() + u(rng) * (b.yMax() - b.yMin()),
                      b.zMin() + u(rng) * (b.zMax() - b.zMin()));
}

osg::Vec3d corner(const osg::BoundingBoxd& b, int i)
{
    return osg::Vec3d(i & 1 ? b.xMax() : b.xMin(), i & 2 ? b.yMax() : b.yMin(), i & 4 ? b.zMax() : b.zMin());
}
} // namespace

// measureRange bounds what measure gives anywhere in the box, for every kind.
TEST(SaliencyMetricTest, MeasureRangeContainsEverySampledValue)
{
    std::vector<osg::ref_ptr<RegionOfInterest>> regions = {
        new RegionOfInterest(RegionOfInterest::POLYLINE, {{-200, -100}, {0, 50}, {150, 50}}, 5.0),
        new RegionOfInterest(RegionOfInterest::POLYGON, {{100, -200}, {250, -200}, {250, -50}, {180, -120}}),
        new RegionOfInterest(RegionOfInterest::CIRCLES, {{-150, 200}, {0, -250}}, 20.0)};
    std::mt19937 rng(42);
    std::uniform_real_distribution<double> e(-400.0, 400.0), h(-50.0, 300.0);
    for (int trial = 0; trial < 400; ++trial)
    {
        SaliencyView v = viewFrom(osg::Vec3d(e(rng), e(rng), h(rng)));
        v.regions = &regions;
        v.focus = randomBox(rng);
        const osg::BoundingBoxd box = randomBox(rng);
        for (M::Kind kind : {M::VIEW_DISTANCE, M::VIEW_ANGLE, M::REGION, M::FOCUS, M::FEATURE_INTEREST})
        {
            osg::ref_ptr<M> m = new M(kind, 0.0, 1.0);
            double qMin = 0.0, qMax = 0.0;
            m->measureRange(box, v, 0.3, qMin, qMax);
            ASSERT_LE(qMin, qMax) << M::toString(kind);
            for (int k = 0; k < 60; ++k)
            {
                const osg::Vec3d p = k < 8 ? corner(box, k) : randomPointIn(box, rng);
                const double q = m->measure(p, v, 0.3);
                EXPECT_GE(q, qMin - 1e-9) << M::toString(kind) << " trial " << trial;
                EXPECT_LE(q, qMax + 1e-9) << M::toString(kind) << " trial " << trial;
            }
        }
    }
}

// For VIEW_DISTANCE and VIEW_ANGLE the bounds are exact: attained at a point of the box.
TEST(SaliencyMetricTest, MeasureRangeIsTightForViewDistanceAndAngle)
{
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> e(-400.0, 400.0), h(-50.0, 300.0);
    for (int trial = 0; trial < 500; ++trial)
    {
        const SaliencyView v = viewFrom(osg::Vec3d(e(rng), e(rng), h(rng)));
        const osg::BoundingBoxd box = randomBox(rng);
        // Distance: the farthest point is a corner; the nearest is the eye clamped to the box.
        double qMin = 0.0, qMax = 0.0;
        mk(M::VIEW_DISTANCE, 0.0, 1.0)->measureRange(box, v, 0.0, qMin, qMax);
        double farthest = 0.0;
        for (int i = 0; i < 8; ++i)
            farthest = std::max(farthest, (corner(box, i) - v.eye).length());
        const osg::Vec3d nearest(std::min(box.xMax(), std::max(box.xMin(), v.eye.x())),
                                 std::min(box.yMax(), std::max(box.yMin(), v.eye.y())),
                                 std::min(box.zMax(), std::max(box.zMin(), v.eye.z())));
        EXPECT_NEAR(qMax, farthest, 1e-9);
        EXPECT_NEAR(qMin, (nearest - v.eye).length(), 1e-9);
        // Angle: largest at the bottom of the box horizontally nearest to the eye, smallest at
        // the top corner horizontally farthest from it.
        mk(M::VIEW_ANGLE, 0.0, 1.0)->measureRange(box, v, 0.0, qMin, qMax);
        const osg::Vec3d steepest(nearest.x(), nearest.y(), box.zMin());
        double flattest = 90.0;
        for (int i = 4; i < 8; ++i) // the top corners
            flattest = std::min(flattest, measure(M::VIEW_ANGLE, corner(box, i), v));
        EXPECT_NEAR(qMax, measure(M::VIEW_ANGLE, steepest, v), 1e-9);
        EXPECT_NEAR(qMin, flattest, 1e-9);
    }
    // A hand case: eye (0,0,100), box [50,150]x[0,0]x[0,0] -> distance from sqrt(50²+100²) =
    // 111.80 to sqrt(150²+100²) = 180.28; angle from atan(100/150) = 33.69 to atan(100/50) = 63.43.
    const SaliencyView v = viewFrom(osg::Vec3d(0, 0, 100));
    const osg::BoundingBoxd line(50, 0, 0, 150, 0, 0);
    double qMin = 0.0, qMax = 0.0;
    mk(M::VIEW_DISTANCE, 0.0, 1.0)->measureRange(line, v, 0.0, qMin, qMax);
    EXPECT_NEAR(qMin, 111.803398875, 1e-6);
    EXPECT_NEAR(qMax, 180.277563773, 1e-6);
    mk(M::VIEW_ANGLE, 0.0, 1.0)->measureRange(line, v, 0.0, qMin, qMax);
    EXPECT_NEAR(qMin, 33.690067526, 1e-6);
    EXPECT_NEAR(qMax, 63.434948823, 1e-6);
}

TEST(SaliencyMetricTest, ValidateMessages)
{
    EXPECT_EQ(mk(M::VIEW_DISTANCE, 100.0, 300.0)->validate(), "");
    EXPECT_EQ(mk(M::VIEW_DISTANCE, 100.0, 100.0)->validate(), ""); // a step is valid
    EXPECT_EQ(mk(M::VIEW_DISTANCE, 300.0, 100.0)->validate(),
              "view-distance metric is inverted: near 300 > far 100");
    EXPECT_EQ(mk(M::REGION, -1.0, 100.0)->validate(), "region metric has near -1 < 0");
    EXPECT_EQ(mk(M::FOCUS, 0.0, 100.0, -2.0)->validate(),
              "focus metric has weight -2; it must be finite and >= 0");
    EXPECT_EQ(mk(M::VIEW_ANGLE, 25.0, 95.0)->validate(), "view-angle metric has far 95 > 90 degrees");
    EXPECT_EQ(mk(M::VIEW_ANGLE, 25.0, kInf)->validate(),
              "view-angle metric has a non-finite near or far value");
    EXPECT_EQ(mk(M::VIEW_DISTANCE, std::nan(""), 1.0)->validate(),
              "view-distance metric has a non-finite near or far value");
    EXPECT_EQ(mk(M::VIEW_DISTANCE, 0.0, 1.0, std::nan(""))->validate(),
              "view-distance metric has weight nan; it must be finite and >= 0");
    // Feature interest ignores near and far.
    EXPECT_EQ(mk(M::FEATURE_INTEREST, 5.0, 1.0)->validate(), "");
    EXPECT_EQ(mk(M::FEATURE_INTEREST, 0.0, 0.0, -1.0)->validate(),
              "feature-interest metric has weight -1; it must be finite and >= 0");
}

TEST(SaliencyMetricTest, KindNames)
{
    for (int k = 0; k < M::kNumKinds; ++k)
    {
        M::Kind parsed = M::FEATURE_INTEREST;
        EXPECT_TRUE(M::parseKind(M::toString(M::Kind(k)), parsed)) << k;
        EXPECT_EQ(parsed, M::Kind(k));
    }
    M::Kind kind = M::VIEW_DISTANCE;
    EXPECT_TRUE(M::parseKind("VIEW_ANGLE", kind));
    EXPECT_EQ(kind, M::VIEW_ANGLE);
    EXPECT_FALSE(M::parseKind("loudness", kind));
    EXPECT_EQ(kind, M::VIEW_ANGLE);
}

// --- RegionOfInterest ---------------------------------------------------------------------

TEST(RegionOfInterestTest, DistanceToEachShape)
{
    typedef RegionOfInterest R;
    // Polyline (0,0)-(100,0)-(100,100).
    osg::ref_ptr<R> route = new R(R::POLYLINE, {{0, 0}, {100, 0}, {100, 100}});
    EXPECT_DOUBLE_EQ(route->distance(osg::Vec2d(50, 20)), 20.0);  // above the first segment
    EXPECT_DOUBLE_EQ(route->distance(osg::Vec2d(120, 50)), 20.0); // right of the second
    EXPECT_DOUBLE_EQ(route->distance(osg::Vec2d(-30, 40)), 50.0); // 3-4-5 from (0,0)
    EXPECT_EQ(route->distance(osg::Vec2d(100, 30)), 0.0);         // on the line
    route->setRadius(5.0);
    EXPECT_DOUBLE_EQ(route->distance(osg::Vec2d(-30, 40)), 45.0); // 50 - 5
    EXPECT_EQ(route->distance(osg::Vec2d(50, 4)), 0.0);           // within the radius

    // Square polygon: inside is 0, outside the distance to the ring.
    osg::ref_ptr<R> square = new R(R::POLYGON, {{0, 0}, {100, 0}, {100, 100}, {0, 100}});
    EXPECT_EQ(square->distance(osg::Vec2d(50, 50)), 0.0);
    EXPECT_EQ(square->distance(osg::Vec2d(1, 99)), 0.0);
    EXPECT_DOUBLE_EQ(square->distance(osg::Vec2d(150, 50)), 50.0);
    EXPECT_DOUBLE_EQ(square->distance(osg::Vec2d(130, 140)), 50.0); // 3-4-5 from (100,100)
    square->setRadius(10.0);
    EXPECT_DOUBLE_EQ(square->distance(osg::Vec2d(130, 140)), 40.0);

    // Concave L: (0,0) (100,0) (100,40) (40,40) (40,100) (0,100). The notch [40,100]x[40,100]
    // is outside: (70,70) is 30 from both inner edges.
    osg::ref_ptr<R> ell = new R(R::POLYGON, {{0, 0}, {100, 0}, {100, 40}, {40, 40}, {40, 100}, {0, 100}});
    EXPECT_EQ(ell->validate(), "");
    EXPECT_DOUBLE_EQ(ell->distance(osg::Vec2d(70, 70)), 30.0);
    EXPECT_DOUBLE_EQ(ell->distance(osg::Vec2d(90, 60)), 20.0); // above the lower arm's top (y=40)
    EXPECT_EQ(ell->distance(osg::Vec2d(20, 80)), 0.0);         // in the upper arm
    EXPECT_EQ(ell->distance(osg::Vec2d(80, 20)), 0.0);         // in the lower arm
    EXPECT_DOUBLE_EQ(ell->distance(osg::Vec2d(50, 50)), 10.0); // 10 from (40,50) and (50,40)
    // Clockwise order gives the same region.
    osg::ref_ptr<R> cw = new R(R::POLYGON, {{0, 100}, {40, 100}, {40, 40}, {100, 40}, {100, 0}, {0, 0}});
    EXPECT_DOUBLE_EQ(cw->distance(osg::Vec2d(70, 70)), 30.0);
    EXPECT_EQ(cw->distance(osg::Vec2d(20, 80)), 0.0);

    // Circles: the nearest disc.
    osg::ref_ptr<R> discs = new R(R::CIRCLES, {{0, 0}, {100, 0}}, 10.0);
    EXPECT_DOUBLE_EQ(discs->distance(osg::Vec2d(30, 40)), 40.0);  // 50 from (0,0)
    EXPECT_DOUBLE_EQ(discs->distance(osg::Vec2d(100, 30)), 20.0); // 30 from (100,0)
    EXPECT_EQ(discs->distance(osg::Vec2d(95, 0)), 0.0);
    // Radius 0: the points themselves.
    osg::ref_ptr<R> points = new R(R::CIRCLES, {{10, 10}});
    EXPECT_DOUBLE_EQ(points->distance(osg::Vec2d(13, 14)), 5.0);
}

TEST(RegionOfInterestTest, Bound)
{
    typedef RegionOfInterest R;
    const osg::BoundingBoxd c = mr(R::CIRCLES, {{10, 20}}, 5.0)->bound();
    ASSERT_TRUE(c.valid());
    EXPECT_EQ(c._min, osg::Vec3d(5, 15, 0));
    EXPECT_EQ(c._max, osg::Vec3d(15, 25, 0));
    const osg::BoundingBoxd p = mr(R::POLYLINE, {{0, 0}, {100, -50}, {30, 80}}, 2.0)->bound();
    EXPECT_EQ(p._min, osg::Vec3d(-2, -52, 0));
    EXPECT_EQ(p._max, osg::Vec3d(102, 82, 0));
    EXPECT_FALSE(mr(R::POLYGON, {{0, 0}, {1, 1}})->bound().valid());
    EXPECT_FALSE(mr(R::POLYLINE, {{0, 0}})->bound().valid());
    EXPECT_FALSE(mr()->bound().valid());
}

TEST(RegionOfInterestTest, DegenerateShapesValidateAndAreAbsent)
{
    typedef RegionOfInterest R;
    osg::ref_ptr<R> two = new R(R::POLYGON, {{0, 0}, {10, 0}});
    two->setName("old town");
    EXPECT_EQ(two->validate(), "polygon 'old town' has 2 vertices; it needs at least 3");
    EXPECT_EQ(two->distance(osg::Vec2d(0, 0)), kInf);
    EXPECT_EQ(mr()->validate(), "circles has 0 vertices; it needs at least 1");
    EXPECT_EQ(mr()->distance(osg::Vec2d(0, 0)), kInf);
    EXPECT_EQ(mr(R::POLYLINE, {{0, 0}})->validate(), "polyline has 1 vertices; it needs at least 2");
    EXPECT_EQ(mr(R::POLYLINE, {{0, 0}})->distance(osg::Vec2d(0, 0)), kInf);
    // Three collinear vertices enclose nothing.
    EXPECT_EQ(mr(R::POLYGON, {{0, 0}, {5, 5}, {10, 10}})->validate(), "polygon has zero area");
    EXPECT_EQ(mr(R::POLYGON, {{0, 0}, {0, 0}, {0, 0}, {0, 0}})->validate(), "polygon has zero area");
    EXPECT_EQ(mr(R::POLYLINE, {{0, 0}, {std::nan(""), 1}})->validate(), "polyline has a non-finite vertex");
    EXPECT_EQ(mr(R::POLYGON, {{0, 0}, {1, 0}, {0, 1}})->validate(), "");
    EXPECT_EQ(mr(R::CIRCLES, {{3, 4}}, 0.0)->validate(), "");
}

TEST(RegionOfInterestTest, NegativeOrNonFiniteRadiusThrows)
{
    typedef RegionOfInterest R;
    osg::ref_ptr<R> r = new R(R::CIRCLES, {{0, 0}}, 1.0);
    EXPECT_THROW(r->setRadius(-1.0), std::invalid_argument);
    EXPECT_THROW(r->setRadius(std::nan("")), std::invalid_argument);
    EXPECT_THROW(r->setRadius(kInf), std::invalid_argument);
    EXPECT_EQ(r->getRadius(), 1.0); // unchanged
    EXPECT_THROW(mr(R::CIRCLES, {{0, 0}}, -0.5), std::invalid_argument);
    r->setRadius(0.0);
    EXPECT_EQ(r->getRadius(), 0.0);
}

TEST(RegionOfInterestTest, ShapeNames)
{
    typedef RegionOfInterest R;
    R::Shape s = R::CIRCLES;
    EXPECT_TRUE(R::parseShape("Polygon", s));
    EXPECT_EQ(s, R::POLYGON);
    EXPECT_TRUE(R::parseShape("POLYLINE", s));
    EXPECT_EQ(s, R::POLYLINE);
    EXPECT_FALSE(R::parseShape("triangle", s));
    EXPECT_STREQ(R::toString(R::CIRCLES), "circles");
}
