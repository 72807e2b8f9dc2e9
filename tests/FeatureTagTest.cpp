// The feature tag convention and its survival through .osgt and .osgb round trips.
#include "support/TestSupport.h"

#include <osgLoA/city/CityGenerator>
#include <osgLoA/semantics/FeatureTag>

#include <osg/Group>
#include <osgDB/ReadFile>
#include <osgDB/WriteFile>

#include <gtest/gtest.h>

using namespace osgLoA;

TEST(FeatureTagTest, ApplyAndReadBack)
{
    osg::ref_ptr<osg::Group> g = new osg::Group;
    FeatureTag t;
    t.id = 42;
    t.type = FeatureType::Water;
    t.subtype = "lake";
    t.landmark = true;
    t.apply(*g);
    EXPECT_EQ(g->getName(), "Water_42");
    FeatureTag r;
    ASSERT_TRUE(FeatureTag::read(*g, r));
    EXPECT_EQ(r.id, 42u);
    EXPECT_EQ(r.type, FeatureType::Water);
    EXPECT_EQ(r.subtype, "lake");
    EXPECT_TRUE(r.landmark);
    osg::ref_ptr<osg::Group> plain = new osg::Group;
    EXPECT_FALSE(FeatureTag::read(*plain, r));
}

TEST(FeatureTagTest, TypeNamesParseCaseInsensitively)
{
    FeatureType t = FeatureType::Generic;
    EXPECT_TRUE(parseFeatureType("Building", t));
    EXPECT_EQ(t, FeatureType::Building);
    EXPECT_TRUE(parseFeatureType("GREEN", t));
    EXPECT_EQ(t, FeatureType::Green);
    EXPECT_FALSE(parseFeatureType("railway", t));
}

// Write, read, write again: the two files must be identical, and the tags intact.
TEST(FeatureTagTest, TagsSurviveOsgtAndOsgbRoundTrips)
{
    const std::string dir = loatest::freshDirectory("FeatureTagTest");
    osg::ref_ptr<osg::Group> city = CityGenerator(CityParameters::small()).generate();
    const std::string first = loatest::toOsgt(*city);
    for (const char* ext : {"osgt", "osgb"})
    {
        const std::string path = dir + "/city." + ext;
        ASSERT_TRUE(osgDB::writeNodeFile(*city, path, new osgDB::Options("WriteImageHint=IncludeData")));
        osg::ref_ptr<osg::Node> back = osgDB::readRefNodeFile(path);
        ASSERT_TRUE(back.valid()) << path;
        EXPECT_EQ(loatest::toOsgt(*back), first) << ext << " round trip changed the graph";
    }
}
