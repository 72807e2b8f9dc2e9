// The landscape scenario (paper 004 Figure 9F; ScenarioLibrary "landscape"): seen from the top
// camera with its map band brought near, so that every feature is in it, each feature type is
// drawn exactly as its
// cartographic device draws it alone (relief, waterlining, signatures, streets, cartographic, all
// in the brewer-subtypes colours), on the demo city and on West Oakland (OpenStreetMap), at
// 1920x1080 and an odd size; from the oblique camera the near part stays photorealistic.
#include "support/TestSupport.h"
#include "support/TopDownView.h"

#include <osgLoA/city/CityCameras>
#include <osgLoA/city/CityGenerator>
#include <osgLoA/render/OffscreenRenderer>
#include <osgLoA/styles/GraphicStyleCatalog>
#include <osgLoA/transitions/LoANode>
#include <osgLoA/transitions/ScenarioLibrary>

#include <osgDB/FileUtils>
#include <osgDB/ReadFile>

#include <gtest/gtest.h>

#include <array>
#include <iostream>

using namespace osgLoA;

namespace
{
/** A style drawing each feature type in a pure colour of its own, unlit edges aside. */
void registerTypeMask()
{
    static bool done = false;
    if (done) return;
    done = true;
    osg::ref_ptr<GraphicStyle> mask = GraphicStyleCatalog::instance().create("cartographic");
    mask->setName("test-type-mask");
    const osg::Vec3f colours[6] = {osg::Vec3f(1, 0, 1), osg::Vec3f(1, 0, 0), osg::Vec3f(0, 1, 0),
                                   osg::Vec3f(0, 0, 1), osg::Vec3f(1, 1, 0), osg::Vec3f(0, 1, 1)};
    for (unsigned i = 0; i < 6; ++i)
        mask->getParameter("loa_cartographic_colors")->setElement(i, colours[i]);
    mask->setEdgeStrength(0.0f);
    mask->setUnsharpMaskStrength(0.0f);
    GraphicStyleCatalog::instance().add(*mask);
    // Streets without their label layer: labels lie over every type (StreetLabelsGLTest tests them).
    osg::ref_ptr<GraphicStyle> streets = GraphicStyleCatalog::instance().create("streets");
    streets->setName("test-streets-unlabelled");
    streets->getParameter("loa_labels_size")->set(0.0f);
    GraphicStyleCatalog::instance().add(*streets);
}

/** The feature type a mask pixel shows (by which channels are lit), -1 for the background. */
int typeOf(const unsigned char* p)
{
    const bool r = p[0] > 60, g = p[1] > 60, b = p[2] > 60;
    const int code = (r ? 4 : 0) | (g ? 2 : 0) | (b ? 1 : 0);
    // magenta generic, red building, green street, blue water, yellow green space, cyan terrain
    switch (code)
    {
    case 5:
        return 0;
    case 4:
        return 1;
    case 2:
        return 2;
    case 1:
        return 3;
    case 6:
        return 4;
    case 3:
        return 5;
    default:
        return -1;
    }
}

osg::ref_ptr<osg::Image> render(osg::Node* model, UsageScenario* scenario, const std::string& camera, int w,
                                int h)
{
    osg::ref_ptr<LoANode> loa = new LoANode;
    loa->setScenario(scenario);
    loa->addChild(model);
    OffscreenRenderer::Settings s;
    s.width = w;
    s.height = h;
    osg::ref_ptr<OffscreenRenderer> r = new OffscreenRenderer(s);
    r->setSceneData(loa.get());
    const CameraPose pose = CityCameras::compute(camera, *model, double(w) / h);
    r->setPerspective(pose.fovy);
    r->setViewMatrixAsLookAt(pose.eye, pose.center, pose.up);
    osg::ref_ptr<osg::Image> image = r->renderImage();
    EXPECT_EQ(loa->getBindError(), "");
    return image;
}

osg::ref_ptr<UsageScenario> homogeneous(const std::string& style)
{
    osg::ref_ptr<UsageScenario> s = ScenarioLibrary::createHomogeneous(style);
    s->setColorScheme("brewer-subtypes");
    return s;
}

/** Per type, the pixels where the landscape frame differs from its device's frame. */
void expectEachTypeInItsDevice(const std::string& name, osg::Node* model, int w, int h)
{
    registerTypeMask();
    osg::ref_ptr<UsageScenario> landscape = ScenarioLibrary::createBuiltin("landscape");
    ASSERT_TRUE(landscape->validate().ok());
    // The map band brought within 0.1-0.2 D of the camera, so that the whole top view (whose
    // nearest point, below the camera, is D away) is in it.
    for (const auto& c : landscape->getConfigurations())
    {
        for (const auto& m : c->getMetrics())
        {
            m->setNear(0.1);
            m->setFar(0.2);
        }
        if (c->getStyle() == "streets") c->setStyle("test-streets-unlabelled");
    }
    osg::ref_ptr<osg::Image> frame = render(model, landscape.get(), "top", w, h);
    osg::ref_ptr<osg::Image> mask =
        render(model, ScenarioLibrary::createHomogeneous("test-type-mask").get(), "top", w, h);
    const std::string size = std::to_string(w) + "x" + std::to_string(h);
    loatest::keepFrame("landscape", *frame, name + "-top-" + size);
    const char* devices[6] = {"cartographic", "cartographic", "test-streets-unlabelled",
                              "waterlining",  "signatures",   "relief"};
    std::array<osg::ref_ptr<osg::Image>, 6> reference;
    for (int t = 0; t < 6; ++t)
        reference[std::size_t(t)] =
            t == 1 ? reference[0] : render(model, homogeneous(devices[t]).get(), "top", w, h);
    std::array<long, 6> pixels{}, differing{};
    for (int y = 1; y + 1 < h; ++y)
        for (int x = 1; x + 1 < w; ++x)
        {
            const int t = typeOf(mask->data(x, y));
            // Inside a type's area (its 3 x 3 neighbourhood of one type: edges between features of
            // two devices are drawn by the one in front in either frame, but blended differently).
            bool interior = t >= 0;
            for (int j = -1; j <= 1 && interior; ++j)
                for (int i = -1; i <= 1 && interior; ++i)
                    interior = typeOf(mask->data(x + i, y + j)) == t;
            if (!interior) continue;
            ++pixels[std::size_t(t)];
            const unsigned char *p = frame->data(x, y), *q = reference[std::size_t(t)]->data(x, y);
            differing[std::size_t(t)] +=
                std::max({std::abs(p[0] - q[0]), std::abs(p[1] - q[1]), std::abs(p[2] - q[2])}) > 2;
        }
    const char* typeNames[6] = {"generic", "building", "street", "water", "green", "terrain"};
    for (int t = 0; t < 6; ++t)
    {
        std::cout << "landscape " << name << " " << size << ": " << typeNames[t] << " "
                  << differing[std::size_t(t)] << " of " << pixels[std::size_t(t)] << " pixels differ from "
                  << devices[t] << "\n";
        EXPECT_LE(double(differing[std::size_t(t)]), 0.002 * double(pixels[std::size_t(t)]) + 2.0)
            << name << " " << typeNames[t];
    }
}
} // namespace

TEST(LandscapeScenarioGLTest, EachTypeInItsDeviceOnTheDemoCity)
{
    osg::ref_ptr<osg::Node> city = CityGenerator(CityParameters()).generate();
    expectEachTypeInItsDevice("demo-city", city.get(), 1920, 1080);
    expectEachTypeInItsDevice("demo-city", city.get(), 641, 359);
}

TEST(LandscapeScenarioGLTest, EachTypeInItsDeviceOnARealOsmFile)
{
    const std::string file = std::string(LOA_SOURCE_DIR) + "/data/cache/python-osmnx-doc/West-Oakland.osm";
    if (!osgDB::fileExists(file)) GTEST_SKIP() << file << " is absent: run scripts/fetch-test-data";
    osg::ref_ptr<osg::Node> model = osgDB::readRefNodeFile(file);
    ASSERT_TRUE(model.valid());
    expectEachTypeInItsDevice("west-oakland", model.get(), 1920, 1080);
}

// From the oblique camera the near part of the demo city is detailed: the frame there equals the
// photorealistic frame, and the far part is the map.
TEST(LandscapeScenarioGLTest, NearIsPhotorealisticFarIsTheMap)
{
    osg::ref_ptr<osg::Node> city = CityGenerator(CityParameters()).generate();
    const int w = 1920, h = 1080;
    osg::ref_ptr<osg::Image> frame =
        render(city.get(), ScenarioLibrary::createBuiltin("landscape").get(), "oblique", w, h);
    osg::ref_ptr<osg::Image> photo =
        render(city.get(), ScenarioLibrary::createHomogeneous("photorealistic").get(), "oblique", w, h);
    loatest::keepFrame("landscape", *frame, "demo-city-oblique-1920x1080");
    auto share = [&](int y0, int y1)
    {
        long same = 0, n = 0;
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < w; ++x, ++n)
            {
                const unsigned char *p = frame->data(x, y), *q = photo->data(x, y);
                same += std::max({std::abs(p[0] - q[0]), std::abs(p[1] - q[1]), std::abs(p[2] - q[2])}) <= 2;
            }
        return double(same) / double(n);
    };
    // Window rows count from the bottom: the bottom tenth is the near ground, the band above the
    // city's far edge (rows 60-70 % up) the distant part.
    const double nearSame = share(0, h / 10), farSame = share(6 * h / 10, 7 * h / 10);
    std::cout << "landscape oblique: " << 100 * nearSame << " % of the near rows and " << 100 * farSame
              << " % of the far rows equal photorealistic\n";
    EXPECT_GT(nearSame, 0.95);
    EXPECT_LT(farSame, 0.5);
}
