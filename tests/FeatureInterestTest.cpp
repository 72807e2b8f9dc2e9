// FeatureInterest: interest per type and per feature, the landmark threshold, validation, and
// write-read-write round trips through .osgt and .osgb (plugins/serializers/osgLoA/FeatureInterest.cpp).
#include "support/TestSupport.h"

#include <osgLoA/city/CityGenerator>
#include <osgLoA/semantics/FeatureIndex>
#include <osgLoA/semantics/FeatureInterest>

#include <osg/Group>
#include <osgDB/ReadFile>
#include <osgDB/WriteFile>

#include <gtest/gtest.h>

#include <fstream>
#include <limits>
#include <sstream>

using namespace osgLoA;

namespace
{
/** A scene of six features: ids 1..6 of types building, building, street, water, green, generic;
 *  feature 2 comes from model data with interest 1.0 and the landmark flag (as the demo city's
 *  landmarks do), feature 4 with interest 0.5. */
osg::ref_ptr<osg::Group> sixFeatures()
{
    osg::ref_ptr<osg::Group> root = new osg::Group;
    const FeatureType types[] = {FeatureType::Building, FeatureType::Building, FeatureType::Street,
                                 FeatureType::Water,    FeatureType::Green,    FeatureType::Generic};
    for (unsigned i = 0; i < 6; ++i)
    {
        osg::ref_ptr<osg::Group> g = new osg::Group;
        osg::ref_ptr<Feature> f = new Feature(i + 1, types[i]);
        if (i == 1)
        {
            f->setInterest(1.0f);
            f->setLandmark(true);
        }
        if (i == 3) f->setInterest(0.5f);
        Feature::attach(*g, f.get());
        root->addChild(g);
    }
    return root;
}

float interestOf(const FeatureIndex& index, unsigned id)
{
    return index.find(id)->feature->getInterest();
}
bool landmark(const FeatureIndex& index, unsigned id)
{
    return index.find(id)->feature->getLandmark();
}

template <typename F> std::string invalidArgumentMessage(F f)
{
    try
    {
        f();
    }
    catch (const std::invalid_argument& e)
    {
        return e.what();
    }
    return "(no exception)";
}
} // namespace

TEST(FeatureInterestTest, Defaults)
{
    osg::ref_ptr<FeatureInterest> fi = new FeatureInterest;
    EXPECT_FLOAT_EQ(fi->getLandmarkThreshold(), 0.8f);
    EXPECT_FLOAT_EQ(fi->getDefaultInterest(), 0.0f);
    EXPECT_FALSE(fi->getKeepExistingInterest());
    for (FeatureType t : kFeatureTypes)
    {
        EXPECT_FALSE(fi->hasTypeInterest(t));
        EXPECT_EQ(fi->getTypeInterest(t), 0.0f);
    }
}

// Without the keep flag, everything unset becomes the default interest 0, so even the model's
// landmark (feature 2) loses its flag: 0 landmarks.
TEST(FeatureInterestTest, DefaultsResetEveryInterestToZero)
{
    osg::ref_ptr<osg::Group> root = sixFeatures();
    FeatureIndex index(*root);
    osg::ref_ptr<FeatureInterest> fi = new FeatureInterest;
    EXPECT_EQ(fi->apply(index), 0u);
    for (unsigned id = 1; id <= 6; ++id)
    {
        EXPECT_EQ(interestOf(index, id), 0.0f) << id;
        EXPECT_FALSE(landmark(index, id)) << id;
    }
}

// Precedence: override by id > type value > existing value (keep flag) > default.
//   building 0.3, water 0.9, green 0.8 (= threshold), override id 1 -> 0.95, id 5 -> 0.1,
//   keep flag on, default 0.2.
//   id 1 building: override 0.95         -> landmark
//   id 2 building: type 0.3 (beats its model value 1.0) -> not
//   id 3 street:   no type value, existing 0 kept -> 0, not
//   id 4 water:    type 0.9 (beats existing 0.5) -> landmark
//   id 5 green:    override 0.1 (beats type 0.8) -> not
//   id 6 generic:  existing 0 kept        -> not
// => 2 landmarks.
TEST(FeatureInterestTest, PrecedenceOverrideTypeExistingDefault)
{
    osg::ref_ptr<osg::Group> root = sixFeatures();
    FeatureIndex index(*root);
    osg::ref_ptr<FeatureInterest> fi = new FeatureInterest;
    fi->setTypeInterest(FeatureType::Building, 0.3f);
    fi->setTypeInterest(FeatureType::Water, 0.9f);
    fi->setTypeInterest(FeatureType::Green, 0.8f);
    fi->setFeatureInterest(1, 0.95f);
    fi->setFeatureInterest(5, 0.1f);
    fi->setKeepExistingInterest(true);
    fi->setDefaultInterest(0.2f);
    EXPECT_EQ(fi->apply(index), 2u);
    EXPECT_FLOAT_EQ(interestOf(index, 1), 0.95f);
    EXPECT_FLOAT_EQ(interestOf(index, 2), 0.3f);
    EXPECT_FLOAT_EQ(interestOf(index, 3), 0.0f);
    EXPECT_FLOAT_EQ(interestOf(index, 4), 0.9f);
    EXPECT_FLOAT_EQ(interestOf(index, 5), 0.1f);
    EXPECT_FLOAT_EQ(interestOf(index, 6), 0.0f);
    EXPECT_TRUE(landmark(index, 1));
    EXPECT_FALSE(landmark(index, 2));
    EXPECT_TRUE(landmark(index, 4));
    EXPECT_FALSE(landmark(index, 5));

    // Without the keep flag, street and generic (no type value, no override) get the default 0.2.
    fi->setKeepExistingInterest(false);
    fi->apply(index);
    EXPECT_FLOAT_EQ(interestOf(index, 3), 0.2f);
    EXPECT_FLOAT_EQ(interestOf(index, 6), 0.2f);

    // Interest exactly at the threshold is a landmark (>=): green at 0.8 once id 5's override goes.
    fi->removeFeatureInterest(5);
    EXPECT_EQ(fi->apply(index), 3u);
    EXPECT_TRUE(landmark(index, 5));
}

// Keep flag with no type values: the model's values stay (2 -> 1.0 landmark, 4 -> 0.5 not); a
// lower threshold of 0.5 makes feature 4 one too.
TEST(FeatureInterestTest, KeepFlagKeepsModelDataInterest)
{
    osg::ref_ptr<osg::Group> root = sixFeatures();
    FeatureIndex index(*root);
    osg::ref_ptr<FeatureInterest> fi = new FeatureInterest;
    fi->setKeepExistingInterest(true);
    EXPECT_EQ(fi->apply(index), 1u);
    EXPECT_FLOAT_EQ(interestOf(index, 2), 1.0f);
    EXPECT_FLOAT_EQ(interestOf(index, 4), 0.5f);
    EXPECT_TRUE(landmark(index, 2));
    fi->setLandmarkThreshold(0.5f);
    EXPECT_EQ(fi->apply(index), 2u);
    EXPECT_TRUE(landmark(index, 4));
}

// The demo city sets interest 1.0 on its landmarks: keeping them reproduces the generator's flags.
TEST(FeatureInterestTest, DemoCityLandmarksSurviveWithKeepFlag)
{
    osg::ref_ptr<osg::Group> city = CityGenerator(CityParameters::small()).generate();
    FeatureIndex index(*city);
    const unsigned before = index.counts(false).landmarks;
    ASSERT_GT(before, 0u);
    osg::ref_ptr<FeatureInterest> fi = new FeatureInterest;
    fi->setKeepExistingInterest(true);
    EXPECT_EQ(fi->apply(index), before);
}

TEST(FeatureInterestTest, ValuesOutsideTheUnitIntervalOrNaNAreRejected)
{
    osg::ref_ptr<FeatureInterest> fi = new FeatureInterest;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_NE(invalidArgumentMessage([&] { fi->setLandmarkThreshold(1.5f); }).find("1.5"), std::string::npos);
    EXPECT_NE(invalidArgumentMessage([&] { fi->setLandmarkThreshold(nan); }).find("nan"), std::string::npos);
    EXPECT_NE(invalidArgumentMessage([&] { fi->setTypeInterest(FeatureType::Water, -0.25f); }).find("-0.25"),
              std::string::npos);
    EXPECT_NE(invalidArgumentMessage([&] { fi->setFeatureInterest(7, 2.0f); }).find("2"), std::string::npos);
    EXPECT_NE(invalidArgumentMessage([&] { fi->setDefaultInterest(nan); }).find("nan"), std::string::npos);
    FeatureInterest::TypeInterests bad{{FeatureType::Green, 0.5f}, {FeatureType::Street, 1.25f}};
    EXPECT_NE(invalidArgumentMessage([&] { fi->setTypeInterests(bad); }).find("1.25"), std::string::npos);
    // A rejected value changes nothing.
    EXPECT_FLOAT_EQ(fi->getLandmarkThreshold(), 0.8f);
    EXPECT_TRUE(fi->getTypeInterests().empty());
    EXPECT_TRUE(fi->getFeatureInterests().empty());
    // The bounds themselves are valid.
    fi->setLandmarkThreshold(0.0f);
    fi->setLandmarkThreshold(1.0f);
    fi->setTypeInterest(FeatureType::Terrain, 0.0f);
    fi->setTypeInterest(FeatureType::Terrain, 1.0f);
}

TEST(FeatureInterestTest, CopyConstructorCopiesEverything)
{
    osg::ref_ptr<FeatureInterest> a = new FeatureInterest;
    a->setTypeInterest(FeatureType::Street, 0.4f);
    a->setFeatureInterest(9, 0.6f);
    a->setKeepExistingInterest(true);
    a->setLandmarkThreshold(0.7f);
    a->setDefaultInterest(0.1f);
    osg::ref_ptr<FeatureInterest> b = static_cast<FeatureInterest*>(a->clone(osg::CopyOp::DEEP_COPY_ALL));
    EXPECT_EQ(b->getTypeInterests(), a->getTypeInterests());
    EXPECT_EQ(b->getFeatureInterests(), a->getFeatureInterests());
    EXPECT_TRUE(b->getKeepExistingInterest());
    EXPECT_FLOAT_EQ(b->getLandmarkThreshold(), 0.7f);
    EXPECT_FLOAT_EQ(b->getDefaultInterest(), 0.1f);
}

namespace
{
std::string objectToOsgt(const osg::Object& o, const std::string& path)
{
    EXPECT_TRUE(osgDB::writeObjectFile(o, path));
    std::ifstream in(path);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}
} // namespace

// Every field non-default; write, read, write again: identical text and equal fields.
TEST(FeatureInterestTest, EveryFieldSurvivesOsgtAndOsgbRoundTrips)
{
    const std::string dir = loatest::freshDirectory("FeatureInterestTest");
    osg::ref_ptr<FeatureInterest> fi = new FeatureInterest;
    fi->setName("tourist");
    fi->setTypeInterest(FeatureType::Building, 0.25f);
    fi->setTypeInterest(FeatureType::Water, 0.875f);
    fi->setTypeInterest(FeatureType::Generic, 0.0f);
    fi->setFeatureInterest(17, 1.0f);
    fi->setFeatureInterest(4294967295u, 0.5f);
    fi->setDefaultInterest(0.125f);
    fi->setKeepExistingInterest(true);
    fi->setLandmarkThreshold(0.625f);
    const std::string first = objectToOsgt(*fi, dir + "/first.osgt");
    EXPECT_NE(first.find("osgLoA::FeatureInterest"), std::string::npos) << first;
    EXPECT_NE(first.find("water 0.875"), std::string::npos) << first;
    for (const char* ext : {"osgt", "osgb"})
    {
        const std::string path = dir + "/interest." + ext;
        ASSERT_TRUE(osgDB::writeObjectFile(*fi, path));
        osg::ref_ptr<FeatureInterest> r = dynamic_cast<FeatureInterest*>(osgDB::readObjectFile(path));
        ASSERT_TRUE(r.valid()) << path;
        EXPECT_EQ(objectToOsgt(*r, dir + "/second-" + ext + ".osgt"), first) << ext;
        EXPECT_EQ(r->getName(), "tourist");
        EXPECT_EQ(r->getTypeInterests(), fi->getTypeInterests());
        EXPECT_EQ(r->getFeatureInterests(), fi->getFeatureInterests());
        EXPECT_FLOAT_EQ(r->getDefaultInterest(), 0.125f);
        EXPECT_TRUE(r->getKeepExistingInterest());
        EXPECT_FLOAT_EQ(r->getLandmarkThreshold(), 0.625f);
    }
    // Default object: empty maps are not written and read back empty.
    osg::ref_ptr<FeatureInterest> empty = new FeatureInterest;
    ASSERT_TRUE(osgDB::writeObjectFile(*empty, dir + "/empty.osgb"));
    osg::ref_ptr<FeatureInterest> e =
        dynamic_cast<FeatureInterest*>(osgDB::readObjectFile(dir + "/empty.osgb"));
    ASSERT_TRUE(e.valid());
    EXPECT_TRUE(e->getTypeInterests().empty());
    EXPECT_TRUE(e->getFeatureInterests().empty());
    EXPECT_FLOAT_EQ(e->getLandmarkThreshold(), 0.8f);
}

// A file with a value outside [0,1] fails to read (null object), whichever field holds it; it
// does not throw out of osgDB.
TEST(FeatureInterestTest, OutOfRangeValuesInAFileFailTheRead)
{
    const std::string dir = loatest::freshDirectory("FeatureInterestTestBad");
    const std::string head = "#Ascii Object\n#Version 161\n#Generator OpenSceneGraph 3.6.5\n\n"
                             "osgLoA::FeatureInterest {\n  UniqueID 1\n";
    const char* bodies[] = {
        "  LandmarkThreshold 1.5\n", "  DefaultInterest -0.5\n", "  TypeInterests 1 {\n    water 2\n  }\n",
        "  TypeInterests 1 {\n    railway 0.5\n  }\n", "  FeatureInterests 1 {\n    3 7\n  }\n"};
    int i = 0;
    for (const char* body : bodies)
    {
        const std::string path = dir + "/bad" + std::to_string(i++) + ".osgt";
        std::ofstream(path) << head << body << "}\n";
        osg::ref_ptr<osg::Object> o;
        EXPECT_NO_THROW(o = osgDB::readRefObjectFile(path)) << body;
        EXPECT_FALSE(o.valid()) << body;
    }
    // The same file with valid values reads.
    const std::string good = dir + "/good.osgt";
    // (fields in the wrapper's order, as .osgt requires)
    std::ofstream(good) << head << "  TypeInterests 1 {\n    water 1\n  }\n  LandmarkThreshold 0.5\n}\n";
    osg::ref_ptr<FeatureInterest> fi = dynamic_cast<FeatureInterest*>(osgDB::readRefObjectFile(good).get());
    ASSERT_TRUE(fi.valid());
    EXPECT_FLOAT_EQ(fi->getLandmarkThreshold(), 0.5f);
    EXPECT_FLOAT_EQ(fi->getTypeInterest(FeatureType::Water), 1.0f);
}
