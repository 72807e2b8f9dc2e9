// The Feature model: attaching to nodes, the index, and write-read-write round trips through
// .osgt and .osgb (the serializer wrapper in plugins/serializers/osgLoA/Feature.cpp).
#include "support/TestSupport.h"

#include <osgLoA/city/CityGenerator>
#include <osgLoA/semantics/Feature>
#include <osgLoA/semantics/FeatureIndex>

#include <osg/Geode>
#include <osg/Geometry>
#include <osg/Group>
#include <osg/MatrixTransform>
#include <osg/ShapeDrawable>
#include <osgDB/ReadFile>
#include <osgDB/Registry>
#include <osgDB/WriteFile>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <sstream>

using namespace osgLoA;

TEST(FeatureTest, AttachGetDetach)
{
    osg::ref_ptr<osg::Group> g = new osg::Group;
    EXPECT_EQ(Feature::get(*g), nullptr);
    Feature* f = Feature::attach(*g, new Feature(42, FeatureType::Water, "lake"));
    EXPECT_EQ(g->getName(), "Water_42");
    ASSERT_EQ(Feature::get(*g), f);
    EXPECT_EQ(f->getSource(), Feature::MODEL_DATA);
    // Attaching again replaces, and an author's node name is kept.
    g->setName("Lake Constance");
    Feature::attach(*g, new Feature(43, FeatureType::Water, "sea"));
    EXPECT_EQ(g->getUserDataContainer()->getNumUserObjects(), 1u);
    EXPECT_EQ(Feature::get(*g)->getId(), 43u);
    EXPECT_EQ(g->getName(), "Lake Constance");
    EXPECT_TRUE(Feature::detach(*g));
    EXPECT_EQ(Feature::get(*g), nullptr);
    EXPECT_FALSE(Feature::detach(*g));
}

TEST(FeatureTest, InterestIsClampedToTheUnitInterval)
{
    osg::ref_ptr<Feature> f = new Feature;
    f->setInterest(1.5f);
    EXPECT_EQ(f->getInterest(), 1.0f);
    f->setInterest(-0.2f);
    EXPECT_EQ(f->getInterest(), 0.0f);
    f->setInterest(std::numeric_limits<float>::quiet_NaN());
    EXPECT_EQ(f->getInterest(), 0.0f);
    f->setInterest(0.25f);
    EXPECT_EQ(f->getInterest(), 0.25f);
}

TEST(FeatureTest, TypeNamesParseCaseInsensitively)
{
    FeatureType t = FeatureType::Generic;
    EXPECT_TRUE(parseFeatureType("Building", t));
    EXPECT_EQ(t, FeatureType::Building);
    EXPECT_TRUE(parseFeatureType("GREEN", t));
    EXPECT_EQ(t, FeatureType::Green);
    EXPECT_FALSE(parseFeatureType("railway", t));
}

// Nested features, world-space bounds through a transform, numbering and counts.
TEST(FeatureTest, IndexCollectsNestsBoundsAndCounts)
{
    osg::ref_ptr<osg::Group> root = new osg::Group;
    osg::ref_ptr<osg::MatrixTransform> xf = new osg::MatrixTransform(osg::Matrix::translate(100, 0, 0));
    root->addChild(xf);
    osg::ref_ptr<osg::Group> building = new osg::Group;
    Feature::attach(*building, new Feature(7, FeatureType::Building));
    xf->addChild(building);
    osg::ref_ptr<osg::Geode> part = new osg::Geode;
    part->addDrawable(new osg::ShapeDrawable(new osg::Box(osg::Vec3(0, 0, 5), 2, 4, 10)));
    Feature::attach(*part, new Feature(0, FeatureType::Building, "part"));
    building->addChild(part);
    osg::ref_ptr<osg::Geode> pond = new osg::Geode;
    pond->addDrawable(new osg::ShapeDrawable(new osg::Box(osg::Vec3(0, 0, 0), 6, 6, 0.5f)));
    osg::ref_ptr<Feature> pf = new Feature(3, FeatureType::Water);
    pf->setInterest(0.9f);
    pf->setLandmark(true);
    Feature::attach(*pond, pf.get());
    root->addChild(pond);

    FeatureIndex index(*root);
    ASSERT_EQ(index.size(), 3u);
    EXPECT_EQ(index.entries()[0].feature->getId(), 7u);
    EXPECT_EQ(index.entries()[1].parent, 0);
    EXPECT_EQ(index.entries()[2].parent, -1);
    EXPECT_EQ(index.numberUnnumbered(), 1u);
    EXPECT_EQ(index.entries()[1].feature->getId(), 8u); // above the largest id, 7
    EXPECT_TRUE(index.duplicateIds().empty());
    index.updateBounds();
    const osg::BoundingBoxf& b = index.find(7)->feature->getBound();
    EXPECT_FLOAT_EQ(b.xMin(), 99.0f);
    EXPECT_FLOAT_EQ(b.xMax(), 101.0f);
    EXPECT_FLOAT_EQ(b.yMin(), -2.0f);
    EXPECT_FLOAT_EQ(b.zMax(), 10.0f);
    const FeatureIndex::Counts top = index.counts();
    EXPECT_EQ(top.total, 2u);
    EXPECT_EQ(top.get(FeatureType::Building), 1u);
    EXPECT_EQ(top.get(FeatureType::Water), 1u);
    EXPECT_EQ(top.landmarks, 1u);
    EXPECT_EQ(index.counts(false).get(FeatureType::Building), 2u);
    EXPECT_EQ(top.toJson(), "{\"building\": 1, \"street\": 0, \"water\": 1, \"green\": 0, \"terrain\": 0, "
                            "\"generic\": 0, \"landmarks\": 1}");
    Feature::attach(*pond, new Feature(7, FeatureType::Water));
    index.build(*root);
    EXPECT_EQ(index.duplicateIds(), std::vector<unsigned>{7u});
}

// Every field set to a non-default value; write, read, write again: identical text, equal fields.
TEST(FeatureTest, EveryFieldSurvivesOsgtAndOsgbRoundTrips)
{
    const std::string dir = loatest::freshDirectory("FeatureTest");
    osg::ref_ptr<osg::Group> g = new osg::Group;
    osg::ref_ptr<Feature> f = new Feature(12345, FeatureType::Green, "coniferous", Feature::APPEARANCE);
    f->setInterest(0.625f);
    f->setLandmark(true);
    f->setBestViewDirection(osg::Vec3(0.6f, -0.8f, 0.0f));
    f->setBound(osg::BoundingBoxf(-1.5f, 2, 3, 4, 5.25f, 6));
    f->setLod(2.2f);
    f->setSourceId("NL.IMBAG.Pand.0503100000000010");
    f->setSourceType("PlantCover");
    f->setCentreline({osg::Vec2d(1.5, -2.0), osg::Vec2d(30.25, 4.0)});
    f->setLabel("Stra\xc3\x9f"
                "e des 17. Juni");
    Feature::attach(*g, f.get());
    const std::string first = loatest::toOsgt(*g);
    EXPECT_NE(first.find("osgLoA::Feature"), std::string::npos) << first;
    for (const char* ext : {"osgt", "osgb"})
    {
        const std::string path = dir + "/feature." + ext;
        ASSERT_TRUE(osgDB::writeNodeFile(*g, path));
        osg::ref_ptr<osg::Node> back = osgDB::readRefNodeFile(path);
        ASSERT_TRUE(back.valid()) << path;
        EXPECT_EQ(loatest::toOsgt(*back), first) << ext;
        const Feature* r = Feature::get(*back);
        ASSERT_NE(r, nullptr) << ext;
        EXPECT_EQ(r->getId(), 12345u);
        EXPECT_EQ(r->getType(), FeatureType::Green);
        EXPECT_EQ(r->getSubType(), "coniferous");
        EXPECT_EQ(r->getSource(), Feature::APPEARANCE);
        EXPECT_EQ(r->getInterest(), 0.625f);
        EXPECT_TRUE(r->getLandmark());
        EXPECT_EQ(r->getBestViewDirection(), osg::Vec3(0.6f, -0.8f, 0.0f));
        EXPECT_EQ(r->getBound()._min, osg::Vec3(-1.5f, 2, 3));
        EXPECT_EQ(r->getBound()._max, osg::Vec3(4, 5.25f, 6));
        EXPECT_FLOAT_EQ(r->getLod(), 2.2f);
        EXPECT_EQ(r->getSourceId(), "NL.IMBAG.Pand.0503100000000010");
        EXPECT_EQ(r->getSourceType(), "PlantCover");
        EXPECT_EQ(r->getCentreline(), (Feature::Centreline{osg::Vec2d(1.5, -2.0), osg::Vec2d(30.25, 4.0)}));
        EXPECT_EQ(r->getLabel(), "Stra\xc3\x9f"
                                 "e des 17. Juni");
    }
}

// The whole demo city: write, read, write again gives the same text.
TEST(FeatureTest, DemoCityFeaturesSurviveOsgtAndOsgbRoundTrips)
{
    const std::string dir = loatest::freshDirectory("FeatureTestCity");
    osg::ref_ptr<osg::Group> city = CityGenerator(CityParameters::small()).generate();
    const std::string first = loatest::toOsgt(*city);
    const FeatureIndex::Counts before = FeatureIndex(*city).counts();
    for (const char* ext : {"osgt", "osgb"})
    {
        const std::string path = dir + "/city." + ext;
        ASSERT_TRUE(osgDB::writeNodeFile(
            *city, path,
            osg::ref_ptr<osgDB::Options>(new osgDB::Options("WriteImageHint=IncludeData")).get()));
        osg::ref_ptr<osg::Node> back = osgDB::readRefNodeFile(path);
        ASSERT_TRUE(back.valid()) << path;
        EXPECT_EQ(loatest::toOsgt(*back), first) << ext << " round trip changed the graph";
        const FeatureIndex::Counts after = FeatureIndex(*back).counts();
        EXPECT_EQ(after.toJson(), before.toJson());
        EXPECT_GT(after.total, 20u);
    }
}

// An unknown type or source name in a file fails the read with a message naming it, instead of
// silently becoming the first enumerator (OSG's own enum serializer reads unknown names as 0).
TEST(FeatureTest, UnknownEnumNamesFailTheRead)
{
    osg::ref_ptr<Feature> f = new Feature(7, FeatureType::Water, "river", Feature::RULE);
    osgDB::ReaderWriter* rw = osgDB::Registry::instance()->getReaderWriterForExtension("osgt");
    ASSERT_NE(rw, nullptr);
    osg::ref_ptr<osgDB::Options> ascii = new osgDB::Options;
    ascii->setPluginStringData("fileType", "Ascii");
    std::ostringstream out;
    ASSERT_TRUE(rw->writeObject(*f, out, ascii.get()).success());
    const std::string text = out.str();
    ASSERT_NE(text.find("Type water"), std::string::npos) << text;
    ASSERT_NE(text.find("Source RULE"), std::string::npos) << text;
    for (const std::pair<std::string, std::string>& edit :
         {std::make_pair(std::string("Type water"), std::string("Type lava")),
          std::make_pair(std::string("Source RULE"), std::string("Source GUESS")),
          std::make_pair(std::string("Type water"), std::string("Type 99"))})
    {
        std::string bad = text;
        bad.replace(bad.find(edit.first), edit.first.size(), edit.second);
        std::istringstream in(bad);
        osgDB::ReaderWriter::ReadResult rr = rw->readObject(in, ascii.get());
        EXPECT_FALSE(rr.success() && rr.getObject()) << edit.second;
        EXPECT_NE(rr.message().find(edit.second.substr(edit.second.find(' ') + 1)), std::string::npos)
            << edit.second << ": " << rr.message();
    }
}
