// FeatureClassifier: rule matching and ordering, the default rule set, level precedence, the
// appearance-grouping fallback, model data, rule-set files and round trips, and the demo city
// classified from its names, materials and textures alone.
#include "support/TestSupport.h"

#include <osgLoA/city/CityGenerator>
#include <osgLoA/semantics/Appearance>
#include <osgLoA/semantics/CityObjectTypes>
#include <osgLoA/semantics/FeatureClassifier>
#include <osgLoA/semantics/FeatureIndex>
#include <osgLoA/util/AtomicFile>
#include <osgLoA/util/ModelValidation>

#include <osg/Geode>
#include <osg/Geometry>
#include <osg/Group>
#include <osg/Material>
#include <osg/MatrixTransform>
#include <osg/ShapeDrawable>
#include <osg/Texture2D>
#include <osgDB/ReadFile>
#include <osgDB/WriteFile>

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <map>
#include <sys/resource.h>

using namespace osgLoA;
using R = ClassificationRule;

namespace
{
osg::ref_ptr<osg::Geometry> quad(const std::string& name = std::string())
{
    osg::ref_ptr<osg::Geometry> g = new osg::Geometry;
    osg::ref_ptr<osg::Vec3Array> v = new osg::Vec3Array;
    v->push_back(osg::Vec3(0, 0, 0));
    v->push_back(osg::Vec3(1, 0, 0));
    v->push_back(osg::Vec3(1, 1, 0));
    v->push_back(osg::Vec3(0, 1, 0));
    g->setVertexArray(v);
    g->addPrimitiveSet(new osg::DrawArrays(GL_QUADS, 0, 4));
    g->setName(name);
    return g;
}

osg::ref_ptr<osg::Geode> geode(const std::string& name, const std::string& drawableName = std::string())
{
    osg::ref_ptr<osg::Geode> g = new osg::Geode;
    g->setName(name);
    g->addDrawable(quad(drawableName));
    return g;
}

osg::ref_ptr<osg::Image> solidImage(const std::string& file, unsigned char r, unsigned char gr,
                                    unsigned char b)
{
    osg::ref_ptr<osg::Image> img = new osg::Image;
    img->allocateImage(8, 8, 1, GL_RGB, GL_UNSIGNED_BYTE);
    for (int i = 0; i < 64; ++i)
    {
        img->data()[3 * i] = r;
        img->data()[3 * i + 1] = gr;
        img->data()[3 * i + 2] = b;
    }
    img->setFileName(file);
    return img;
}

void texture(osg::Node& n, osg::Image* img)
{
    n.getOrCreateStateSet()->setTextureAttributeAndModes(0, new osg::Texture2D(img));
}

void material(osg::Node& n, const osg::Vec4& diffuse, const std::string& name = std::string())
{
    osg::ref_ptr<osg::Material> m = new osg::Material;
    m->setDiffuse(osg::Material::FRONT_AND_BACK, diffuse);
    m->setName(name);
    n.getOrCreateStateSet()->setAttribute(m);
}

// The feature that encloses a node (the node's own or its nearest ancestor's).
const Feature* featureOf(osg::Node& n)
{
    for (osg::Node* p = &n; p; p = p->getNumParents() ? p->getParent(0) : nullptr)
        if (const Feature* f = Feature::get(*p)) return f;
    return nullptr;
}

osg::ref_ptr<ClassificationRuleSet> rules(std::initializer_list<R*> list)
{
    osg::ref_ptr<ClassificationRuleSet> s = new ClassificationRuleSet;
    for (R* r : list)
        s->addRule(r);
    return s;
}
} // namespace

TEST(FeatureClassifierTest, GlobMatchesTheWholeStringRegexAnywhereBothCaseInsensitive)
{
    osg::ref_ptr<R> glob = new R(R::NODE_NAME, R::GLOB, "road*", FeatureType::Street);
    EXPECT_TRUE(glob->matches("Road_12"));
    EXPECT_TRUE(glob->matches("ROAD"));
    EXPECT_FALSE(glob->matches("MainRoad")); // a glob matches the whole string
    osg::ref_ptr<R> regex = new R(R::NODE_NAME, R::REGEX, "road", FeatureType::Street);
    EXPECT_TRUE(regex->matches("MainRoad"));
    EXPECT_FALSE(regex->matches("Rail"));
    regex->setCaseSensitive(true);
    EXPECT_FALSE(regex->matches("MainRoad"));
    EXPECT_TRUE(regex->matches("mainroad"));
    osg::ref_ptr<R> cls = new R(R::TEXTURE_FILE, R::GLOB, "grass_?[0-9].png", FeatureType::Green);
    EXPECT_TRUE(cls->matches("Grass_a7.PNG"));
    EXPECT_FALSE(cls->matches("grass_ab.png"));
}

TEST(FeatureClassifierTest, BrokenRulesAreClearErrors)
{
    osg::ref_ptr<R> bad = new R(R::ANY, R::REGEX, "(unclosed", FeatureType::Water);
    EXPECT_THROW(bad->validate(), std::invalid_argument);
    EXPECT_FALSE(bad->matches("(unclosed"));
    try
    {
        osg::ref_ptr<ClassificationRuleSet> set = rules({new R(R::ANY, R::GLOB, "x", FeatureType::Water),
                                                         new R(R::ANY, R::GLOB, "", FeatureType::Water)});
        set->validate();
        FAIL() << "an empty pattern must not validate";
    }
    catch (const std::invalid_argument& e)
    {
        EXPECT_NE(std::string(e.what()).find("rule 2"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("empty pattern"), std::string::npos) << e.what();
    }
    osg::ref_ptr<ClassificationRuleSet> set = rules({bad.get()});
    osg::ref_ptr<osg::Group> scene = new osg::Group;
    EXPECT_THROW(FeatureClassifier(set.get()).classify(*scene), std::invalid_argument);
    set = rules({});
    set->setAppearanceThreshold(-1.0f);
    EXPECT_THROW(set->validate(), std::invalid_argument);
}

// Each field reads its own strings; the first matching rule wins.
TEST(FeatureClassifierTest, FieldsAndRuleOrder)
{
    osg::ref_ptr<osg::Group> root = new osg::Group;
    osg::ref_ptr<osg::Geode> a = geode("thing");
    a->addDescription("a pond in the park");
    osg::ref_ptr<osg::Geode> b = geode("thing");
    b->setUserValue("surface", std::string("cobblestones"));
    b->setUserValue("storeys", 4);
    osg::ref_ptr<osg::Geode> c = geode("thing");
    material(*c, osg::Vec4(1, 1, 1, 1), "mat_Slate_Roof");
    osg::ref_ptr<osg::Geode> d = geode("thing");
    texture(*d, solidImage("/textures/FIELD_03.jpg", 10, 200, 10));
    root->addChild(a);
    root->addChild(b);
    root->addChild(c);
    root->addChild(d);
    osg::ref_ptr<R> userKey = new R(R::USER_VALUE, R::GLOB, "4", FeatureType::Building, "house");
    userKey->setUserValueKey("storeys");
    osg::ref_ptr<ClassificationRuleSet> set =
        rules({new R(R::NODE_DESCRIPTION, R::REGEX, "pond", FeatureType::Water, "lake"),
               new R(R::NODE_DESCRIPTION, R::REGEX, "park", FeatureType::Green), // later: loses
               userKey.get(), new R(R::USER_VALUE, R::GLOB, "surface=cobble*", FeatureType::Street),
               new R(R::MATERIAL_NAME, R::REGEX, "roof", FeatureType::Building, "roof"),
               new R(R::TEXTURE_FILE, R::GLOB, "field_*.jpg", FeatureType::Green, "field")});
    set->setUseAppearance(false);
    set->setGroupObjects(false); // the four quads lie on each other
    const FeatureClassifier::Report r = FeatureClassifier(set.get()).classify(*root);
    EXPECT_EQ(r.units, 4u);
    EXPECT_EQ(r.byRule, 4u);
    EXPECT_EQ(r.perRule, (std::vector<unsigned>{1, 0, 1, 0, 1, 1}));
    ASSERT_TRUE(Feature::get(*a));
    EXPECT_EQ(Feature::get(*a)->getType(), FeatureType::Water);
    EXPECT_EQ(Feature::get(*a)->getSubType(), "lake");
    EXPECT_EQ(Feature::get(*a)->getSource(), Feature::RULE);
    EXPECT_EQ(Feature::get(*b)->getType(), FeatureType::Building); // key rule precedes key=value rule
    EXPECT_EQ(Feature::get(*b)->getSubType(), "house");
    EXPECT_EQ(Feature::get(*c)->getSubType(), "roof");
    EXPECT_EQ(Feature::get(*d)->getSubType(), "field"); // texture file name without its folder
    EXPECT_EQ(r.featuresMerged, 0u);                    // one drawable per Geode
    EXPECT_EQ(r.featuresCreated, 4u);
}

// What a node says about itself beats what a group above it says, whatever the rule order.
TEST(FeatureClassifierTest, OwnStringsBeatAncestors)
{
    osg::ref_ptr<osg::Group> root = new osg::Group;
    osg::ref_ptr<osg::Group> roads = new osg::Group;
    roads->setName("Roads");
    root->addChild(roads);
    osg::ref_ptr<osg::Geode> segment = geode("segment_1");
    osg::ref_ptr<osg::Geode> lake = geode("Lake");
    roads->addChild(segment);
    roads->addChild(lake);
    osg::ref_ptr<ClassificationRuleSet> set =
        rules({new R(R::NODE_NAME, R::GLOB, "roads", FeatureType::Street),
               new R(R::NODE_NAME, R::GLOB, "lake", FeatureType::Water)});
    FeatureClassifier(set.get()).classify(*root);
    EXPECT_EQ(Feature::get(*segment)->getType(), FeatureType::Street); // inherited from "Roads"
    EXPECT_EQ(Feature::get(*lake)->getType(), FeatureType::Water);     // its own name
}

// A Geode whose drawables disagree keeps one feature per drawable; one whose drawables agree
// gets one feature.
TEST(FeatureClassifierTest, DrawablesSplitOrMergeByTheirTypes)
{
    osg::ref_ptr<osg::Group> root = new osg::Group;
    osg::ref_ptr<osg::Geode> mixed = new osg::Geode;
    mixed->addDrawable(quad("roof_tiles"));
    mixed->addDrawable(quad("lawn"));
    osg::ref_ptr<osg::Geode> house = new osg::Geode;
    house->addDrawable(quad("roof"));
    house->addDrawable(quad("wall"));
    root->addChild(mixed);
    root->addChild(house);
    osg::ref_ptr<ClassificationRuleSet> set = ClassificationRuleSet::createDefault();
    set->setGroupObjects(false); // the quads lie on each other: no touching merge here
    const FeatureClassifier::Report r = FeatureClassifier(set.get()).classify(*root);
    EXPECT_EQ(Feature::get(*mixed), nullptr);
    ASSERT_TRUE(Feature::get(*mixed->getDrawable(0)));
    EXPECT_EQ(Feature::get(*mixed->getDrawable(0))->getType(), FeatureType::Building);
    EXPECT_EQ(Feature::get(*mixed->getDrawable(1))->getType(), FeatureType::Green);
    ASSERT_TRUE(Feature::get(*house));
    EXPECT_EQ(Feature::get(*house)->getType(), FeatureType::Building);
    EXPECT_EQ(Feature::get(*house->getDrawable(0)), nullptr);
    EXPECT_EQ(r.featuresCreated, 3u);
    EXPECT_EQ(r.featuresMerged, 1u);
    // Ids are fresh and unique, and the nodes are named after them.
    FeatureIndex index(*root);
    EXPECT_EQ(index.size(), 3u);
    EXPECT_TRUE(index.duplicateIds().empty());
    EXPECT_EQ(house->getName(), "Building_" + std::to_string(Feature::get(*house)->getId()));
    EXPECT_TRUE(Feature::get(*house)->getBound().valid());
}

// The default rule set on the names a user meets (the issue's list), one Geode each.
TEST(FeatureClassifierTest, DefaultRulesCoverCommonNames)
{
    const std::map<std::string, std::pair<FeatureType, std::string>> expected = {
        {"Road", {FeatureType::Street, ""}},
        {"MainStreet", {FeatureType::Street, ""}},
        {"Freeway", {FeatureType::Street, "major"}},
        {"HIGHWAY_A7", {FeatureType::Street, "major"}},
        {"Railroad", {FeatureType::Street, "railway"}},
        {"Parking_lot", {FeatureType::Street, ""}},
        {"Water", {FeatureType::Water, ""}},
        {"Ocean", {FeatureType::Water, "sea"}},
        {"North Sea", {FeatureType::Water, "sea"}},
        {"Lake", {FeatureType::Water, "lake"}},
        {"River", {FeatureType::Water, "river"}},
        {"Stream", {FeatureType::Water, "river"}},
        {"Canal", {FeatureType::Water, "canal"}},
        {"Grass", {FeatureType::Green, "grass"}},
        {"Grassland", {FeatureType::Green, "grass"}},
        {"Park", {FeatureType::Green, "park"}},
        {"Forest", {FeatureType::Green, "forest"}},
        {"Wood", {FeatureType::Green, "forest"}},
        {"ConiferousForest", {FeatureType::Green, "coniferous"}},
        {"mixed_forest", {FeatureType::Green, "mixed"}},
        {"Scrub", {FeatureType::Green, "scrub"}},
        {"Garden", {FeatureType::Green, "garden"}},
        {"Cemetery", {FeatureType::Green, "cemetery"}},
        {"GolfCourse", {FeatureType::Green, "golfcourse"}},
        {"Urban", {FeatureType::Terrain, "urban"}},
        {"Residential", {FeatureType::Terrain, "residential"}},
        {"Industrial", {FeatureType::Terrain, "industrial"}},
        {"Roof", {FeatureType::Building, ""}},
        {"Wall", {FeatureType::Building, ""}},
        {"Facade", {FeatureType::Building, ""}},
        {"Terrain", {FeatureType::Terrain, ""}},
        {"Ground", {FeatureType::Terrain, ""}},
        {"RoofSurface", {FeatureType::Building, ""}},
        {"TrafficArea", {FeatureType::Street, ""}},
        {"WaterSurface", {FeatureType::Water, ""}},
        {"TINRelief", {FeatureType::Terrain, ""}},
        {"PlantCover", {FeatureType::Green, ""}},
        {"TreeCrown", {FeatureType::Green, ""}},
        {"Box001", {FeatureType::Generic, ""}},
    };
    osg::ref_ptr<osg::Group> root = new osg::Group;
    std::map<std::string, osg::ref_ptr<osg::Geode>> nodes;
    for (const auto& kv : expected)
    {
        nodes[kv.first] = geode(kv.first);
        root->addChild(nodes[kv.first]);
    }
    // All quads lie on each other: grouping objects would merge the touching buildings.
    osg::ref_ptr<ClassificationRuleSet> set = ClassificationRuleSet::createDefault();
    set->setGroupObjects(false);
    const FeatureClassifier::Report r = FeatureClassifier(set.get()).classify(*root);
    for (const auto& kv : expected)
    {
        const Feature* f = Feature::get(*nodes[kv.first]);
        ASSERT_TRUE(f) << kv.first;
        EXPECT_EQ(f->getType(), kv.second.first) << kv.first << " became " << toString(f->getType());
        EXPECT_EQ(f->getSubType(), kv.second.second) << kv.first;
    }
    EXPECT_EQ(r.unclassified, 1u);
    EXPECT_EQ(Feature::get(*nodes["Box001"])->getSource(), Feature::UNCLASSIFIED);
}

// CityJSON object types and OpenStreetMap tags arrive as the importer's semantics.
TEST(FeatureClassifierTest, DefaultRulesReadImporterSemantics)
{
    const std::map<std::string, std::pair<FeatureType, std::string>> expected = {
        {"BuildingPart", {FeatureType::Building, "part"}},
        {"BuildingInstallation", {FeatureType::Building, "installation"}},
        {"Bridge", {FeatureType::Street, "bridge"}},
        {"LandUse", {FeatureType::Terrain, "land-use"}},
        {"CityFurniture", {FeatureType::Generic, "furniture"}},
        {"bldg:Building", {FeatureType::Building, ""}},
        {"Road", {FeatureType::Street, "road"}},
        {"TransportSquare", {FeatureType::Street, "square"}},
        {"WaterBody", {FeatureType::Water, ""}},
        {"SolitaryVegetationObject", {FeatureType::Green, "tree"}},
        {"TINRelief", {FeatureType::Terrain, "relief"}},
        {"building=yes", {FeatureType::Building, ""}},
        {"highway=primary", {FeatureType::Street, "major"}},
        {"highway=residential", {FeatureType::Street, "minor"}},
        {"natural=water", {FeatureType::Water, ""}},
        {"landuse=forest", {FeatureType::Green, "forest"}},
        {"leisure=park", {FeatureType::Green, ""}},
        {"amenity=bench", {FeatureType::Generic, "furniture"}}, // the word "bench"
        {"+NoiseBarrier", {FeatureType::Generic, "barrier"}},   // an extension: by its words
    };
    osg::ref_ptr<osg::Group> root = new osg::Group;
    std::map<std::string, osg::ref_ptr<osg::Geode>> nodes;
    for (const auto& kv : expected)
    {
        osg::ref_ptr<osg::Geode> g = geode("");
        osg::ref_ptr<Feature> f = new Feature(0, FeatureType::Generic, "", Feature::UNCLASSIFIED);
        f->setSourceType(kv.first);
        Feature::attach(*g, f.get());
        g->setName("object");
        nodes[kv.first] = g;
        root->addChild(g);
    }
    FeatureClassifier().classify(*root);
    for (const auto& kv : expected)
    {
        const Feature* f = Feature::get(*nodes[kv.first]);
        EXPECT_EQ(f->getType(), kv.second.first) << kv.first;
        EXPECT_EQ(f->getSubType(), kv.second.second) << kv.first;
    }
}

// Model data stands unless the rule set overrides it; USER assignments always stand.
TEST(FeatureClassifierTest, ModelDataAndUserAssignments)
{
    osg::ref_ptr<osg::Group> root = new osg::Group;
    osg::ref_ptr<osg::Geode> model = geode("Lake");
    Feature::attach(*model, new Feature(1, FeatureType::Building, "", Feature::MODEL_DATA));
    osg::ref_ptr<osg::Geode> user = geode("Lake");
    Feature::attach(*user, new Feature(2, FeatureType::Green, "", Feature::USER));
    root->addChild(model);
    root->addChild(user);
    osg::ref_ptr<ClassificationRuleSet> set = ClassificationRuleSet::createDefault();
    FeatureClassifier::Report r = FeatureClassifier(set.get()).classify(*root);
    EXPECT_EQ(r.keptModelData, 2u);
    EXPECT_EQ(Feature::get(*model)->getType(), FeatureType::Building);
    set->setOverrideModelData(true);
    r = FeatureClassifier(set.get()).classify(*root);
    EXPECT_EQ(Feature::get(*model)->getType(), FeatureType::Water);
    EXPECT_EQ(Feature::get(*model)->getSource(), Feature::RULE);
    EXPECT_EQ(Feature::get(*user)->getType(), FeatureType::Green);
}

TEST(FeatureClassifierTest, AppearanceDistances)
{
    // Pure red against pure red: 0; the CIE76 distance of sRGB red and green is 170.6 (red
    // L*a*b* = 53.24, 80.09, 67.20; green = 87.73, -86.18, 83.18).
    const osg::Vec3 red = Appearance::srgbToLab(osg::Vec3(1, 0, 0));
    EXPECT_NEAR(red.x(), 53.24f, 0.05f);
    EXPECT_NEAR(red.y(), 80.09f, 0.1f);
    EXPECT_NEAR(red.z(), 67.20f, 0.1f);
    const osg::Vec3 green = Appearance::srgbToLab(osg::Vec3(0, 1, 0));
    EXPECT_NEAR((red - green).length(), 170.6f, 0.3f);
    // A 50/50 red/blue texture has two dominant colours of weight 0.5.
    osg::ref_ptr<osg::Image> img = solidImage("", 255, 0, 0);
    for (int i = 32; i < 64; ++i)
    {
        img->data()[3 * i] = 0;
        img->data()[3 * i + 2] = 255;
    }
    const auto d = Appearance::dominantColours(*img);
    ASSERT_EQ(d.size(), 2u);
    EXPECT_NEAR(d[0].weight, 0.5f, 1e-6f);
    EXPECT_NEAR(d[1].weight, 0.5f, 1e-6f);
}

// The paper's fallback: unknown geometry takes the type of classified geometry that looks the
// same; conflicting groups and geometry that looks like nothing classified stay generic.
TEST(FeatureClassifierTest, AppearanceGroupingFallback)
{
    osg::ref_ptr<osg::Group> root = new osg::Group;
    osg::ref_ptr<osg::Image> asphalt = solidImage("tex/t_0001.png", 60, 60, 64);
    osg::ref_ptr<osg::Geode> road = geode("Road_a"), roadLike = geode("obj_17");
    texture(*road, asphalt.get());
    texture(*roadLike, asphalt.get()); // the same image: the same appearance
    osg::ref_ptr<osg::Geode> lake = geode("Lake"), blue = geode("obj_18");
    material(*lake, osg::Vec4(0.10f, 0.30f, 0.80f, 1));
    material(*blue, osg::Vec4(0.12f, 0.31f, 0.78f, 1)); // Delta E about 1.5
    osg::ref_ptr<osg::Geode> red = geode("obj_19");
    material(*red, osg::Vec4(0.8f, 0.1f, 0.1f, 1)); // like nothing classified
    osg::ref_ptr<osg::Image> shared = solidImage("tex/t_0002.png", 120, 110, 90);
    osg::ref_ptr<osg::Geode> p = geode("park"), s = geode("street"), q = geode("obj_20");
    for (osg::Geode* g : {p.get(), s.get(), q.get()})
        texture(*g, shared.get());                   // classified members disagree
    osg::ref_ptr<osg::Geode> bare = geode("obj_21"); // no material, no texture: no appearance
    for (osg::Node* n : std::initializer_list<osg::Node*>{road, roadLike, lake, blue, red, p, s, q, bare})
        root->addChild(n);

    const FeatureClassifier::Report r = FeatureClassifier().classify(*root);
    EXPECT_EQ(Feature::get(*roadLike)->getType(), FeatureType::Street);
    EXPECT_EQ(Feature::get(*roadLike)->getSource(), Feature::APPEARANCE);
    EXPECT_EQ(Feature::get(*blue)->getType(), FeatureType::Water);
    EXPECT_EQ(Feature::get(*blue)->getSubType(), "lake");
    EXPECT_EQ(Feature::get(*blue)->getSource(), Feature::APPEARANCE);
    EXPECT_EQ(Feature::get(*red)->getType(), FeatureType::Generic);
    EXPECT_EQ(Feature::get(*red)->getSource(), Feature::UNCLASSIFIED);
    EXPECT_EQ(Feature::get(*q)->getType(), FeatureType::Generic);
    EXPECT_EQ(Feature::get(*bare)->getType(), FeatureType::Generic);
    EXPECT_EQ(r.byAppearance, 2u);
    EXPECT_EQ(r.appearanceConflicts, 1u);
    EXPECT_EQ(r.unclassified, 3u);

    // With a tight threshold the near-identical blue is no longer "the same".
    osg::ref_ptr<ClassificationRuleSet> tight = ClassificationRuleSet::createDefault();
    tight->setAppearanceThreshold(0.5f);
    FeatureClassifier(tight.get()).classify(*root);
    EXPECT_EQ(Feature::get(*blue)->getType(), FeatureType::Generic);
    EXPECT_EQ(Feature::get(*roadLike)->getType(), FeatureType::Street); // same image: distance 0
    // Without the fallback nothing is classified by appearance.
    tight->setUseAppearance(false);
    EXPECT_EQ(FeatureClassifier(tight.get()).classify(*root).byAppearance, 0u);
    EXPECT_EQ(Feature::get(*roadLike)->getType(), FeatureType::Generic);
}

// The demo city stripped of its features and feature names: names of surfaces and textures
// alone must give every drawable the type the generator meant.
TEST(FeatureClassifierTest, DemoCityIsRecoveredFromSurfaceAndTextureNames)
{
    osg::ref_ptr<osg::Group> city = CityGenerator(CityParameters::small()).generate();
    std::map<osg::Drawable*, FeatureType> truth;
    FeatureIndex before(*city);
    struct Drawables : osg::NodeVisitor
    {
        Drawables() : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN) {}
        void apply(osg::Drawable& d) override { list.push_back(&d); }
        std::vector<osg::Drawable*> list;
    };
    for (const auto& e : before.entries())
    {
        osg::ref_ptr<osg::Node> n;
        ASSERT_TRUE(e.node.lock(n));
        Drawables d;
        n->accept(d);
        for (osg::Drawable* dr : d.list)
            truth[dr] = e.feature->getType();
        Feature::detach(*n);
        n->setName("");
    }
    ASSERT_GT(truth.size(), 30u);
    const FeatureClassifier::Report r = FeatureClassifier().classify(*city);
    std::map<FeatureType, std::pair<unsigned, unsigned>> perType; // right, total
    for (const auto& kv : truth)
    {
        const Feature* f = featureOf(*kv.first);
        ASSERT_TRUE(f);
        auto& c = perType[kv.second];
        c.first += f->getType() == kv.second;
        ++c.second;
    }
    for (const auto& kv : perType)
        EXPECT_EQ(kv.second.first, kv.second.second)
            << toString(kv.first) << ": " << kv.second.first << " of " << kv.second.second
            << " drawables right; " << r.summary();
    EXPECT_EQ(r.unclassified, 0u) << r.summary();
    // Classifying again changes nothing.
    const std::string once = loatest::toOsgt(*city);
    FeatureClassifier().classify(*city);
    EXPECT_EQ(loatest::toOsgt(*city), once);
}

// A rule set written by hand in .osgt loads, classifies, and survives write-read-write.
TEST(FeatureClassifierTest, RuleFilesLoadAndRoundTrip)
{
    const std::string dir = loatest::freshDirectory("FeatureClassifierTest");
    const std::string hand = dir + "/mine.osgt";
    AtomicFile::writeText(hand, R"(#Ascii Scene
#Version 161
#Generator by hand

osgLoA::ClassificationRuleSet {
  UniqueID 1
  Rules 2 {
    osgLoA::ClassificationRule {
      UniqueID 2
      Field TEXTURE_FILE
      Pattern "asph*"
      Type street
      SubType "minor"
    }
    osgLoA::ClassificationRule {
      UniqueID 3
      Field NODE_NAME
      Syntax REGEX
      Pattern "^pool[0-9]+$"
      Type water
    }
  }
  UseAppearance FALSE
}
)");
    osg::ref_ptr<ClassificationRuleSet> set = ClassificationRuleSet::read(hand);
    ASSERT_EQ(set->getRules().size(), 2u);
    EXPECT_EQ(set->getRules()[0]->getField(), R::TEXTURE_FILE);
    EXPECT_EQ(set->getRules()[0]->getSyntax(), R::GLOB);
    EXPECT_EQ(set->getRules()[1]->getType(), FeatureType::Water);
    EXPECT_FALSE(set->getUseAppearance());
    osg::ref_ptr<osg::Group> root = new osg::Group;
    osg::ref_ptr<osg::Geode> pool = geode("Pool12");
    root->addChild(pool);
    FeatureClassifier(set.get()).classify(*root);
    EXPECT_EQ(Feature::get(*pool)->getType(), FeatureType::Water);

    // The default set: write, read, write again gives the same bytes, in .osgt and .osgb.
    osg::ref_ptr<ClassificationRuleSet> def = ClassificationRuleSet::createDefault();
    def->setAppearanceThreshold(7.5f);
    def->getRules()[3]->setUserValueKey("k");
    def->getRules()[4]->setCaseSensitive(true);
    for (const char* ext : {"osgt", "osgb"})
    {
        const std::string a = dir + "/default-a." + ext, b = dir + "/default-b." + ext;
        def->write(a);
        osg::ref_ptr<ClassificationRuleSet> back = ClassificationRuleSet::read(a);
        ASSERT_EQ(back->getRules().size(), def->getRules().size());
        for (std::size_t i = 0; i < def->getRules().size(); ++i)
            EXPECT_EQ(back->getRules()[i]->describe(), def->getRules()[i]->describe()) << i;
        EXPECT_TRUE(back->getRules()[4]->getCaseSensitive());
        EXPECT_EQ(back->getAppearanceThreshold(), 7.5f);
        back->write(b);
        std::ifstream fa(a, std::ios::binary), fb(b, std::ios::binary);
        const std::string ta((std::istreambuf_iterator<char>(fa)), {}),
            tb((std::istreambuf_iterator<char>(fb)), {});
        EXPECT_EQ(ta, tb) << ext;
    }
    // Errors name the file and the problem.
    try
    {
        ClassificationRuleSet::read(dir + "/missing.osgt");
        FAIL();
    }
    catch (const std::runtime_error& e)
    {
        EXPECT_NE(std::string(e.what()).find("missing.osgt"), std::string::npos) << e.what();
    }
    osg::ref_ptr<osg::Group> notRules = new osg::Group;
    ASSERT_TRUE(osgDB::writeObjectFile(*notRules, dir + "/group.osgt"));
    try
    {
        ClassificationRuleSet::read(dir + "/group.osgt");
        FAIL();
    }
    catch (const std::runtime_error& e)
    {
        EXPECT_NE(std::string(e.what()).find("not an osgLoA::ClassificationRuleSet"), std::string::npos)
            << e.what();
    }
}

// ---- issue 18: words, inheritance, file-level names, objects -----------------------------

TEST(FeatureClassifierTest, TokensSplitAtSeparatorsCaseChangesAndDigits)
{
    using V = std::vector<std::string>;
    EXPECT_EQ(R::tokenize("tr-building1.rgb"), (V{"tr", "building", "1", "rgb"}));
    EXPECT_EQ(R::tokenize("TireWall"), (V{"tire", "wall"}));
    EXPECT_EQ(R::tokenize("HTMLParser_02"), (V{"html", "parser", "02"}));
    EXPECT_EQ(R::tokenize("ground_z=12.5"), (V{"ground", "z", "12", "5"}));
    EXPECT_EQ(R::tokenize("Fa\xC3\xA7"
                          "ade"),
              (V{"fa\xC3\xA7"
                 "ade"}));
    EXPECT_EQ(R::tokenize(""), V{});
}

TEST(FeatureClassifierTest, TokenRulesMatchWordsNotSubstrings)
{
    osg::ref_ptr<R> wall = new R(R::ANY, R::TOKENS, "wall", FeatureType::Building);
    EXPECT_TRUE(wall->matches("WallSurface"));
    EXPECT_TRUE(wall->matches("north_walls_03"));
    EXPECT_FALSE(wall->matches("tr-tirewall.rgb")); // one word "tirewall"
    EXPECT_FALSE(wall->matches("Wallace"));
    osg::ref_ptr<R> wood = new R(R::ANY, R::TOKENS, "wood|mixed forest", FeatureType::Green);
    EXPECT_FALSE(wood->matches("Hollywood"));
    EXPECT_TRUE(wood->matches("MixedForest_2"));
    EXPECT_FALSE(wood->matches("forest mixed"));
    osg::ref_ptr<R> plural = new R(R::ANY, R::TOKENS, "tree|bush|city|build*", FeatureType::Green);
    EXPECT_TRUE(plural->matches("trees"));
    EXPECT_TRUE(plural->matches("Bushes"));
    EXPECT_TRUE(plural->matches("cities"));
    EXPECT_TRUE(plural->matches("buildings_lod2"));
    EXPECT_FALSE(plural->matches("treetop")); // "tree" without '*' is the word only
    EXPECT_FALSE(plural->matches("rebuild"));
    for (const char* bad : {"a||b", "*x", "a.b", "|", "road(s)"})
    {
        osg::ref_ptr<R> r = new R(R::ANY, R::TOKENS, bad, FeatureType::Street);
        EXPECT_THROW(r->validate(), std::invalid_argument) << bad;
        EXPECT_FALSE(r->matches("a b road x"));
    }
}

TEST(FeatureClassifierTest, RootFileLevelGroupsAndAreaNamesDoNotTypeTheirSubtree)
{
    // A scene named after a street circuit, a file group "street-1.ac", a ProxyNode "streets",
    // an area group "industrial": none of them types the unnamed geometry below it; a group
    // named "roads" (a thing, inheritable) does.
    osg::ref_ptr<osg::Group> root = new osg::Group;
    root->setName("Street Circuit");
    osg::ref_ptr<osg::Group> file = new osg::Group;
    file->setName("street-1.ac");
    root->addChild(file);
    osg::ref_ptr<osg::Geode> loose = geode("");
    file->addChild(loose);
    osg::ref_ptr<osg::Group> industrial = new osg::Group;
    industrial->setName("industrial");
    osg::ref_ptr<osg::Geode> plant = geode("");
    industrial->addChild(plant);
    file->addChild(industrial);
    osg::ref_ptr<osg::Group> roads = new osg::Group;
    roads->setName("roads");
    osg::ref_ptr<osg::Geode> segment = geode("");
    roads->addChild(segment);
    file->addChild(roads);
    osg::ref_ptr<osg::Geode> ownName = geode("industrial"); // its own name: a land-use area
    file->addChild(ownName);
    FeatureClassifier().classify(*root);
    EXPECT_EQ(featureOf(*loose)->getType(), FeatureType::Generic);
    EXPECT_EQ(featureOf(*plant)->getType(), FeatureType::Generic);
    EXPECT_EQ(featureOf(*segment)->getType(), FeatureType::Street);
    EXPECT_EQ(featureOf(*ownName)->getType(), FeatureType::Terrain);
    EXPECT_EQ(featureOf(*ownName)->getSubType(), "industrial");
}

TEST(FeatureClassifierTest, KeyValueDescriptionsAreDataNotNames)
{
    // 13 pylons with the description "ground_z=..." were 26 terrain features.
    osg::ref_ptr<osg::Group> root = new osg::Group;
    osg::ref_ptr<osg::Geode> pylon = geode("pylon_07");
    pylon->addDescription("ground_z=412.5");
    root->addChild(pylon);
    osg::ref_ptr<osg::Geode> described = geode("");
    described->addDescription("old ground level");
    root->addChild(described);
    FeatureClassifier().classify(*root);
    EXPECT_EQ(featureOf(*pylon)->getType(), FeatureType::Generic);
    EXPECT_EQ(featureOf(*pylon)->getSubType(), "furniture");
    EXPECT_EQ(featureOf(*described)->getType(), FeatureType::Terrain); // a description in words
    // An explicit NODE_DESCRIPTION rule still sees key=value text.
    osg::ref_ptr<osg::Group> root2 = new osg::Group;
    osg::ref_ptr<osg::Geode> g = geode("");
    g->addDescription("ground_z=412.5");
    root2->addChild(g);
    FeatureClassifier(rules({new R(R::NODE_DESCRIPTION, R::GLOB, "ground_z=*", FeatureType::Terrain)}).get())
        .classify(*root2);
    EXPECT_EQ(featureOf(*g)->getType(), FeatureType::Terrain);
}

TEST(FeatureClassifierTest, RulesOverrideModelDataOnlyWhenTheySaySo)
{
    auto scene = [](osg::ref_ptr<osg::Geode>& node)
    {
        osg::ref_ptr<osg::Group> root = new osg::Group;
        node = geode("tire wall 3");
        Feature::attach(*node, new Feature(5, FeatureType::Building, "", Feature::MODEL_DATA));
        root->addChild(node);
        return root;
    };
    osg::ref_ptr<osg::Geode> n;
    osg::ref_ptr<osg::Group> root = scene(n);
    osg::ref_ptr<R> barrier = new R(R::NODE_NAME, R::TOKENS, "tire wall", FeatureType::Generic, "barrier");
    FeatureClassifier::Report r = FeatureClassifier(rules({barrier.get()}).get()).classify(*root);
    EXPECT_EQ(Feature::get(*n)->getType(), FeatureType::Building);
    EXPECT_EQ(r.keptModelData, 1u);
    root = scene(n);
    barrier->setOverridesModelData(true);
    r = FeatureClassifier(rules({barrier.get()}).get()).classify(*root);
    EXPECT_EQ(Feature::get(*n)->getType(), FeatureType::Generic);
    EXPECT_EQ(Feature::get(*n)->getSubType(), "barrier");
    EXPECT_EQ(Feature::get(*n)->getSource(), Feature::RULE);
    EXPECT_EQ(r.byRule, 1u);
    // A user's own assignment is never overridden.
    root = scene(n);
    Feature::get(*n)->setSource(Feature::USER);
    FeatureClassifier(rules({barrier.get()}).get()).classify(*root);
    EXPECT_EQ(Feature::get(*n)->getType(), FeatureType::Building);
}

TEST(FeatureClassifierTest, UserRulesComeBeforeTheDefaults)
{
    osg::ref_ptr<ClassificationRuleSet> user =
        rules({new R(R::NODE_NAME, R::TOKENS, "tower", FeatureType::Generic, "mast")});
    user->setUseAppearance(false);
    osg::ref_ptr<ClassificationRuleSet> both = ClassificationRuleSet::withDefaults(*user);
    EXPECT_EQ(both->getRules().size(), 1 + ClassificationRuleSet::createDefault()->getRules().size());
    EXPECT_FALSE(both->getUseAppearance());
    osg::ref_ptr<osg::Group> root = new osg::Group;
    osg::ref_ptr<osg::Geode> tower = geode("radio tower");
    osg::ref_ptr<osg::Geode> lake = geode("lake");
    root->addChild(tower);
    root->addChild(lake);
    FeatureClassifier(both.get()).classify(*root);
    EXPECT_EQ(featureOf(*tower)->getSubType(), "mast");
    EXPECT_EQ(featureOf(*lake)->getType(), FeatureType::Water); // the defaults still apply
}

namespace
{
osg::ref_ptr<osg::Geode> box(const std::string& name, const osg::Vec3& min, const osg::Vec3& max)
{
    osg::ref_ptr<osg::Geode> g = new osg::Geode;
    g->setName(name);
    g->addDrawable(new osg::ShapeDrawable(
        new osg::Box((min + max) * 0.5f, max.x() - min.x(), max.y() - min.y(), max.z() - min.z())));
    return g;
}

unsigned distinctFeatures(osg::Node& root)
{
    return FeatureIndex(root).counts().total;
}
} // namespace

TEST(FeatureClassifierTest, OneObjectOneFeature)
{
    // A transform holding geometry only is one object per type; touching building pieces
    // outside transforms are one building; touching streets are not merged.
    osg::ref_ptr<osg::Group> root = new osg::Group;
    osg::ref_ptr<osg::MatrixTransform> house = new osg::MatrixTransform(osg::Matrix::translate(100, 0, 0));
    house->setName("house-family");
    osg::ref_ptr<osg::Group> inner = new osg::Group;
    inner->addChild(box("walls", {0, 0, 0}, {10, 10, 6}));
    inner->addChild(box("roof", {0, 0, 6}, {10, 10, 9}));
    inner->addChild(box("plot", {-2, -2, -0.1f}, {12, 12, 0}));
    osg::ref_ptr<osg::Geode> tree = box("small tree", {11, 11, 0}, {12, 12, 3});
    inner->addChild(tree);
    house->addChild(inner);
    root->addChild(house);
    osg::ref_ptr<osg::MatrixTransform> shop = new osg::MatrixTransform(osg::Matrix::translate(200, 0, 0));
    shop->setName("shop");
    shop->addChild(box("box", {0, 0, 0}, {6, 6, 4}));
    shop->addChild(box("sign", {0, -1, 4}, {6, 0, 5})); // its own word: furniture
    shop->addChild(box("box", {0, 0, 4}, {6, 6, 5}));
    root->addChild(shop);
    // Walls and roof of one house, touching; a second house 5 m away; two touching streets.
    osg::ref_ptr<osg::Geode> w1 = box("walls", {0, 50, 0}, {8, 58, 5});
    osg::ref_ptr<osg::Geode> r1 = box("roof", {0, 50, 5.02f}, {8, 58, 8});
    osg::ref_ptr<osg::Geode> w2 = box("walls", {13, 50, 0}, {20, 58, 5});
    osg::ref_ptr<osg::Geode> s1 = box("road", {0, 30, 0}, {50, 36, 0.1f});
    osg::ref_ptr<osg::Geode> s2 = box("road", {50, 30, 0}, {90, 36, 0.1f});
    // A tower touching the first house, in another material: a building of its own.
    osg::ref_ptr<osg::Geode> tower = box("tower", {8, 50, 0}, {12, 54, 30});
    material(*tower, osg::Vec4(0.8f, 0.2f, 0.2f, 1));
    for (osg::Node* n : {w1.get(), r1.get(), w2.get(), s1.get(), s2.get(), tower.get()})
        root->addChild(n);
    const FeatureClassifier::Report report = FeatureClassifier().classify(*root);
    EXPECT_EQ(report.units, 13u);
    // The house transform: one building (walls, roof, plot on each Geode, one Feature) and one
    // tree; the shop: one building, and its sign.
    osg::Group* pieces = inner.get();
    EXPECT_EQ(featureOf(*pieces->getChild(0))->getType(), FeatureType::Building);
    EXPECT_EQ(featureOf(*pieces->getChild(0)), featureOf(*pieces->getChild(1)));
    EXPECT_EQ(featureOf(*pieces->getChild(0)), featureOf(*pieces->getChild(2)));
    EXPECT_EQ(featureOf(*tree)->getType(), FeatureType::Green);
    EXPECT_EQ(Feature::get(*house), nullptr);
    EXPECT_EQ(Feature::get(*shop), nullptr); // the sign is not part of the building feature
    EXPECT_EQ(featureOf(*shop->getChild(0)), featureOf(*shop->getChild(2)));
    EXPECT_EQ(featureOf(*shop->getChild(1))->getSubType(), "furniture");
    EXPECT_EQ(featureOf(*w1), featureOf(*r1));
    EXPECT_NE(featureOf(*w1), featureOf(*w2));
    EXPECT_NE(featureOf(*w1), featureOf(*tower));
    EXPECT_NE(featureOf(*s1), featureOf(*s2));
    const FeatureIndex::Counts c = FeatureIndex(*root).counts();
    EXPECT_EQ(c.get(FeatureType::Building), 5u); // house, shop, w1+r1, w2, tower
    EXPECT_EQ(c.get(FeatureType::Green), 1u);
    EXPECT_EQ(c.get(FeatureType::Street), 2u);
    EXPECT_EQ(c.get(FeatureType::Generic), 1u);
    EXPECT_EQ(c.total, 9u);
    EXPECT_EQ(report.featuresCreated, 9u);
    // One feature on two nodes: its box is the union, its id is no duplicate.
    const osg::BoundingBoxf& b = featureOf(*w1)->getBound();
    EXPECT_NEAR(b.zMax(), 8.0f, 1e-4f);
    EXPECT_NEAR(b.zMin(), 0.0f, 1e-4f);
    EXPECT_TRUE(FeatureIndex(*root).duplicateIds().empty());
    // Classifying again changes nothing.
    FeatureClassifier().classify(*root);
    EXPECT_EQ(distinctFeatures(*root), 9u);

    // Tunable: a gap of 0.02 m is not a touch at tolerance 0.01; grouping off is a feature per Geode.
    osg::ref_ptr<ClassificationRuleSet> strict = ClassificationRuleSet::createDefault();
    strict->setMergeTolerance(0.01f);
    osg::ref_ptr<osg::Group> root2 = new osg::Group;
    root2->addChild(box("walls", {0, 50, 0}, {8, 58, 5}));
    root2->addChild(box("roof", {0, 50, 5.02f}, {8, 58, 8}));
    FeatureClassifier(strict.get()).classify(*root2);
    EXPECT_EQ(distinctFeatures(*root2), 2u);
    osg::ref_ptr<ClassificationRuleSet> off = ClassificationRuleSet::createDefault();
    off->setGroupObjects(false);
    osg::ref_ptr<osg::Group> root3 = new osg::Group;
    osg::ref_ptr<osg::MatrixTransform> t = new osg::MatrixTransform;
    t->setName("house");
    t->addChild(box("a", {0, 0, 0}, {1, 1, 1}));
    t->addChild(box("b", {0, 0, 1}, {1, 1, 2}));
    root3->addChild(t);
    FeatureClassifier(off.get()).classify(*root3);
    EXPECT_EQ(distinctFeatures(*root3), 2u);
    osg::ref_ptr<osg::Group> root4 = new osg::Group; // grouping on: one feature, on the transform
    root4->addChild(t);
    t->getChild(0)->setUserDataContainer(nullptr);
    t->getChild(1)->setUserDataContainer(nullptr);
    FeatureClassifier().classify(*root4);
    EXPECT_EQ(distinctFeatures(*root4), 1u);
    ASSERT_NE(Feature::get(*t), nullptr);
    EXPECT_EQ(Feature::get(*t)->getType(), FeatureType::Building);
    off->setMergeTouchingTypes("building nonsense");
    EXPECT_THROW(off->validate(), std::invalid_argument);
}

// Every CityJSON 2.0 city-object type (the specification's list, typed here from it) has a
// mapping, the issue's examples map as it asks, and docs/classification.md prints the table.
TEST(FeatureClassifierTest, CityObjectTypesCoverCityJson2AndAreDocumented)
{
    const char* const cityJson2[] = {"Bridge",
                                     "BridgePart",
                                     "BridgeInstallation",
                                     "BridgeConstructiveElement",
                                     "BridgeRoom",
                                     "BridgeFurniture",
                                     "Building",
                                     "BuildingPart",
                                     "BuildingInstallation",
                                     "BuildingConstructiveElement",
                                     "BuildingFurniture",
                                     "BuildingStorey",
                                     "BuildingRoom",
                                     "BuildingUnit",
                                     "CityFurniture",
                                     "CityObjectGroup",
                                     "GenericCityObject",
                                     "LandUse",
                                     "OtherConstruction",
                                     "PlantCover",
                                     "SolitaryVegetationObject",
                                     "TINRelief",
                                     "TransportSquare",
                                     "Railway",
                                     "Road",
                                     "Tunnel",
                                     "TunnelPart",
                                     "TunnelInstallation",
                                     "TunnelConstructiveElement",
                                     "TunnelHollowSpace",
                                     "TunnelFurniture",
                                     "WaterBody",
                                     "Waterway"};
    for (const char* t : cityJson2)
        EXPECT_NE(CityObjectTypes::find(t), nullptr) << t;
    const std::map<std::string, FeatureType> issue = {
        {"LandUse", FeatureType::Terrain},        {"TINRelief", FeatureType::Terrain},
        {"Bridge", FeatureType::Street},          {"Railway", FeatureType::Street},
        {"TransportSquare", FeatureType::Street}, {"Tunnel", FeatureType::Street},
        {"PlantCover", FeatureType::Green},       {"SolitaryVegetationObject", FeatureType::Green},
        {"CityFurniture", FeatureType::Generic}};
    for (const auto& kv : issue)
        EXPECT_EQ(CityObjectTypes::find(kv.first)->type, kv.second) << kv.first;
    EXPECT_EQ(CityObjectTypes::find("+NoiseBarrier"), nullptr);
    EXPECT_EQ(CityObjectTypes::find("tran:Road")->type, FeatureType::Street);
    std::ifstream in(std::string(LOA_SOURCE_DIR) + "/docs/classification.md");
    const std::string doc((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (const CityObjectTypes::Entry& e : CityObjectTypes::table())
    {
        std::string row = std::string("| `") + e.name + "` | " + toString(e.type);
        if (*e.subType) row += std::string("/") + e.subType;
        EXPECT_NE(doc.find(row + " |"), std::string::npos) << "docs/classification.md lacks: " << row;
    }
}

// Memory linear in the scene (issue 22 item 3): a chain of nested groups as deep as the tools
// accept (ModelValidation::MAX_SCENE_DEPTH, 4,096), a drawable at each level. One NodePath copy
// per unit made this O(depth^2): 742 MB at 8,000 levels, about 195 MB at 4,096; the units now
// share a path tree. The process's peak resident size must stay below 150 MB. (8,000 levels
// overflowed the 8 MB stack of the visitors under AddressSanitizer.)
TEST(FeatureClassifierTest, DeepChainsTakeLinearMemory)
{
    osg::ref_ptr<osg::Group> root = new osg::Group;
    osg::Group* at = root.get();
    for (int i = 0; i < int(osgLoA::ModelValidation::MAX_SCENE_DEPTH); ++i)
    {
        osg::ref_ptr<osg::Geode> g = new osg::Geode;
        osg::ref_ptr<osg::Geometry> tri = new osg::Geometry;
        osg::ref_ptr<osg::Vec3Array> v = new osg::Vec3Array;
        v->push_back({float(i), 0, 0});
        v->push_back({float(i) + 1, 0, 0});
        v->push_back({float(i), 1, 0});
        tri->setVertexArray(v.get());
        tri->addPrimitiveSet(new osg::DrawArrays(GL_TRIANGLES, 0, 3));
        g->addDrawable(tri.get());
        at->addChild(g.get());
        osg::ref_ptr<osg::Group> next = new osg::Group;
        at->addChild(next.get());
        at = next.get();
    }
    struct rusage before;
    ::getrusage(RUSAGE_SELF, &before);
    const osgLoA::FeatureClassifier::Report r = osgLoA::FeatureClassifier().classify(*root);
    struct rusage after;
    ::getrusage(RUSAGE_SELF, &after);
    EXPECT_EQ(r.units, osgLoA::ModelValidation::MAX_SCENE_DEPTH);
#if defined(__SANITIZE_ADDRESS__)
    // AddressSanitizer's redzones and its quarantine of freed memory (256 MB) make the peak
    // meaningless here; the normal build measures it.
    (void)before, (void)after;
#else
    EXPECT_LT(after.ru_maxrss - before.ru_maxrss, 150L * 1024) << "kB grown by the classification";
#endif
}
