// The .loa pseudo-loader and .loa scenario files (osgdb_loa), as osgviewer and osgconv use them.
#include "support/TestSupport.h"

#include <osgLoA/semantics/ClassificationRuleSet>
#include <osgLoA/semantics/FeatureIndex>
#include <osgLoA/transitions/LoANode>
#include <osgLoA/transitions/ScenarioLibrary>

#include <osg/Geode>
#include <osg/Notify>
#include <osg/ShapeDrawable>
#include <osgDB/FileNameUtils>
#include <osgDB/FileUtils>
#include <osgDB/ReadFile>
#include <osgDB/Registry>
#include <osgDB/WriteFile>

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

namespace
{
// A small demo city that still has every feature type but landmarks (33 features): the
// default 10x8 city takes several times longer to generate and classify.
const std::string kCity = "seed=2 blocksX=4 blocksY=4";

typedef osgDB::ReaderWriter::ReadResult ReadResult;

ReadResult read(const std::string& name, const std::string& optionString = std::string())
{
    osg::ref_ptr<osgDB::Options> opts = new osgDB::Options(optionString);
    return osgDB::Registry::instance()->readNode(name, opts.get());
}

osg::ref_ptr<osgLoA::LoANode> readLoa(const std::string& name,
                                      const std::string& optionString = std::string())
{
    ReadResult rr = read(name, optionString);
    EXPECT_TRUE(rr.validNode()) << name << ": " << rr.statusMessage();
    return dynamic_cast<osgLoA::LoANode*>(rr.getNode());
}

std::string textOf(const std::string& path)
{
    std::ifstream in(path);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

void writeText(const std::string& path, const std::string& text)
{
    std::ofstream(path) << text;
}

/** A scenario as the .osgt text a scenario library holds. */
std::string scenarioText(const osgLoA::UsageScenario& s, const std::string& dir)
{
    const std::string path = dir + "/scenario-text.osgt";
    osgLoA::ScenarioLibrary::writeFile(s, path);
    return textOf(path);
}

/** A model without features: one box. */
std::string writeBox(const std::string& dir)
{
    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    geode->setName("box");
    geode->addDrawable(new osg::ShapeDrawable(new osg::Box(osg::Vec3(0, 0, 5), 10.0f)));
    const std::string path = dir + "/box.osgt";
    EXPECT_TRUE(osgDB::writeNodeFile(*geode, path));
    return path;
}

/** Collects what osg::notify says while it lives. */
class NotifyCapture : public osg::NotifyHandler
{
public:
    void notify(osg::NotifySeverity, const char* message) override { text += message; }
    std::string text;
};

struct ScopedCapture
{
    osg::ref_ptr<NotifyCapture> capture = new NotifyCapture;
    osg::ref_ptr<osg::NotifyHandler> previous = osg::getNotifyHandler();
    osg::NotifySeverity level = osg::getNotifyLevel();
    ScopedCapture()
    {
        osg::setNotifyLevel(osg::WARN);
        osg::setNotifyHandler(capture.get());
    }
    ~ScopedCapture()
    {
        osg::setNotifyHandler(previous.get());
        osg::setNotifyLevel(level);
    }
    const std::string& text() const { return capture->text; }
};

std::string quote(const std::string& s)
{
    return "'" + s + "'";
}

std::string osgconv(const std::string& args, int& rc)
{
    std::string out;
    rc = loatest::run("env " + loatest::stockToolEnvironment() + "OSG_LIBRARY_PATH='" +
                          std::string(LOA_BINARY_DIR) + "/lib' osgconv " + args,
                      out);
    return out;
}

bool haveOsgconv()
{
    std::string out;
    return loatest::run("command -v osgconv", out) == 0;
}
} // namespace

TEST(LoaPluginTest, DemoCityGetsTheDefaultScenarioAndItsFeaturesKeepTheirTypes)
{
    osg::ref_ptr<osgLoA::LoANode> loa = readLoa("demo.loacity.loa", kCity);
    ASSERT_TRUE(loa.valid()) << "osgdb_loa not found on OSG_LIBRARY_PATH, or it did not give a LoANode";
    ASSERT_NE(loa->getScenario(), nullptr);
    EXPECT_EQ(loa->getScenario()->getName(), osgLoA::ScenarioLibrary::defaultName());
    EXPECT_EQ(loa->getNumChildren(), 1u);

    // The city's own features (source MODEL_DATA) are kept as the generator typed them: the
    // counts per type are those of the plain city.
    osg::ref_ptr<osg::Node> plain =
        osgDB::readRefNodeFile("demo.loacity", osg::ref_ptr<osgDB::Options>(new osgDB::Options(kCity)).get());
    ASSERT_TRUE(plain.valid());
    const osgLoA::FeatureIndex::Counts expected = osgLoA::FeatureIndex(*plain).counts();
    osgLoA::FeatureIndex index(*loa);
    const osgLoA::FeatureIndex::Counts counts = index.counts();
    EXPECT_EQ(counts.total, expected.total);
    for (osgLoA::FeatureType t : osgLoA::kFeatureTypes)
        EXPECT_EQ(counts.get(t), expected.get(t)) << osgLoA::toString(t);
    EXPECT_GT(counts.get(osgLoA::FeatureType::Building), 0u);
    EXPECT_GT(counts.get(osgLoA::FeatureType::Green), 0u);
    for (const auto& e : index.entries())
        EXPECT_EQ(e.feature->getSource(), osgLoA::Feature::MODEL_DATA) << e.feature->getId();

    // The scenario binds to those features.
    loa->evaluate(osg::Vec3d(0.0, -900.0, 400.0));
    EXPECT_TRUE(loa->getBindError().empty()) << loa->getBindError();
    ASSERT_NE(loa->getEvaluator(), nullptr);
    EXPECT_TRUE(loa->getEvaluator()->isBound());
}

TEST(LoaPluginTest, ClassifiesAModelWithoutFeatures)
{
    const std::string dir = loatest::freshDirectory("LoaPluginTest-classify");
    const std::string box = writeBox(dir);
    osg::ref_ptr<osgLoA::LoANode> loa = readLoa(box + ".loa");
    ASSERT_TRUE(loa.valid());
    osgLoA::FeatureIndex index(*loa);
    ASSERT_EQ(index.size(), 1u) << "the classifier attaches one feature to the box";
    EXPECT_NE(index.entries()[0].feature->getId(), 0u);
}

TEST(LoaPluginTest, ScenarioOptionPicksALibraryScenario)
{
    // What `osgviewer -O "scenario=route seed=2 ..." demo.loacity.loa` passes: scenario= is the
    // loa plugin's, the city keys go on to osgdb_loacity (which rejects any key it does not know,
    // so this also shows that scenario= is not passed on).
    osg::ref_ptr<osgLoA::LoANode> loa = readLoa("demo.loacity.loa", "scenario=route " + kCity);
    ASSERT_TRUE(loa.valid());
    ASSERT_NE(loa->getScenario(), nullptr);
    EXPECT_EQ(loa->getScenario()->getName(), "route");
    EXPECT_EQ(loa->getScenario()->getRegions().size(), 1u);
    EXPECT_GT(osgLoA::FeatureIndex(*loa).counts().get(osgLoA::FeatureType::Building), 0u)
        << "the city options reached the city reader";
}

TEST(LoaPluginTest, OitOptionSelectsTheOrderIndependentTransparency)
{
    using OIT = osgLoA::OrderIndependentTransparency;
    for (const char* name : {"stencil-routed", "linked-list", "weighted-blended"})
    {
        osg::ref_ptr<osgLoA::LoANode> loa = readLoa("demo.loacity.loa", std::string("oit=") + name + " " + kCity);
        ASSERT_TRUE(loa.valid()) << name;
        EXPECT_EQ(loa->getRenderer()->getSettings().oit, OIT::methodFromName(name));
        EXPECT_STREQ(OIT::methodName(loa->getRenderer()->getABuffer()->getMethod()), name);
        EXPECT_FALSE(loa->getRenderer()->getSettings().oitAuto);
    }
    osg::ref_ptr<osgLoA::LoANode> autoLoa = readLoa("demo.loacity.loa", "oit=auto " + kCity);
    ASSERT_TRUE(autoLoa.valid());
    EXPECT_TRUE(autoLoa->getRenderer()->getSettings().oitAuto);
}

TEST(LoaPluginTest, EveryLibraryScenarioLoadsWithoutWarnings)
{
    // The default city: it holds the blueprint scenario's focus object (its central tower).
    for (const std::string& name : osgLoA::ScenarioLibrary::builtinNames())
    {
        ScopedCapture capture;
        osg::ref_ptr<osgLoA::LoANode> loa = readLoa("demo.loacity.loa", "scenario=" + name);
        ASSERT_TRUE(loa.valid()) << name;
        EXPECT_EQ(loa->getScenario()->getName(), name);
        loa->evaluate(osg::Vec3d(0.0, -900.0, 400.0)); // binds: the node's own warnings too
        EXPECT_TRUE(loa->getBindError().empty()) << name << ": " << loa->getBindError();
        EXPECT_EQ(capture.text(), "") << name;
    }
}

TEST(LoaPluginTest, ScenarioOptionTakesAScenarioFile)
{
    const std::string dir = loatest::freshDirectory("LoaPluginTest-file");
    osg::ref_ptr<osgLoA::UsageScenario> s = osgLoA::ScenarioLibrary::createBuiltin("circular-roi");
    s->setName("my-roi");
    osgLoA::ScenarioLibrary::writeFile(*s, dir + "/my.osgt");
    osg::ref_ptr<osgLoA::LoANode> loa = readLoa("demo.loacity.loa", "scenario=" + dir + "/my.osgt " + kCity);
    ASSERT_TRUE(loa.valid());
    EXPECT_EQ(loa->getScenario()->getName(), "my-roi");
    EXPECT_EQ(scenarioText(*loa->getScenario(), dir), scenarioText(*s, dir));
}

TEST(LoaPluginTest, RulesOptionTakesARuleSetFile)
{
    const std::string dir = loatest::freshDirectory("LoaPluginTest-rules");
    osgLoA::ClassificationRuleSet::createDefault()->write(dir + "/rules.osgt");
    const std::string box = writeBox(dir);
    EXPECT_TRUE(readLoa(box + ".loa", "rules=" + dir + "/rules.osgt").valid());

    ReadResult rr = read(box + ".loa", "rules=" + dir + "/missing-rules.osgt");
    EXPECT_FALSE(rr.validNode());
    EXPECT_NE(rr.message().find("classification rules"), std::string::npos) << rr.message();
    EXPECT_NE(rr.message().find("missing-rules.osgt"), std::string::npos) << rr.message();
}

TEST(LoaPluginTest, KeysForTheModelReaderArePassedOnAndUndeclaredKeysAreReported)
{
    const std::string dir = loatest::freshDirectory("LoaPluginTest-keys");
    const std::string box = writeBox(dir);
    {
        // seed, blocksX and blocksY are keys osgdb_loacity declares: passed on silently.
        ScopedCapture capture;
        EXPECT_TRUE(readLoa("demo.loacity.loa", kCity).valid());
        EXPECT_EQ(capture.text().find("loa:"), std::string::npos) << capture.text();
    }
    {
        // A misspelt scenario key: the .osgt reader does not declare it, so it is reported,
        // with a hint, and the model still loads with the default scenario.
        ScopedCapture capture;
        osg::ref_ptr<osgLoA::LoANode> loa = readLoa(box + ".loa", "senario=route");
        ASSERT_TRUE(loa.valid());
        EXPECT_EQ(loa->getScenario()->getName(), osgLoA::ScenarioLibrary::defaultName());
        EXPECT_NE(capture.text().find("option 'senario' is not a loa option"), std::string::npos)
            << capture.text();
        EXPECT_NE(capture.text().find("did you mean 'scenario='"), std::string::npos) << capture.text();
    }
}

TEST(LoaPluginTest, ErrorsNameTheProblem)
{
    const std::string dir = loatest::freshDirectory("LoaPluginTest-errors");
    struct Case
    {
        const char* what;
        std::string file, options;
        ReadResult::ReadStatus status;
        std::vector<std::string> messageParts;
    };
    osg::ref_ptr<osgLoA::UsageScenario> invalid = new osgLoA::UsageScenario;
    invalid->setName("empty");
    osgLoA::ScenarioLibrary::writeFile(*invalid, dir + "/empty.osgt");
    const Case cases[] = {
        {"unknown OIT method",
         "demo.loacity.loa",
         "oit=depth-peeling " + kCity,
         ReadResult::ERROR_IN_READING_FILE,
         {"oit", "depth-peeling", "linked-list", "auto"}},
        {"unknown scenario name",
         "demo.loacity.loa",
         "scenario=no-such-scenario " + kCity,
         ReadResult::ERROR_IN_READING_FILE,
         {"no scenario named 'no-such-scenario'", "route"}},
        {"missing scenario file",
         "demo.loacity.loa",
         "scenario=" + dir + "/missing.osgt " + kCity,
         ReadResult::ERROR_IN_READING_FILE,
         {"missing.osgt", "not found"}},
        {"scenario that does not validate",
         "demo.loacity.loa",
         "scenario=" + dir + "/empty.osgt " + kCity,
         ReadResult::ERROR_IN_READING_FILE,
         {"empty.osgt", "is not valid"}},
        {"scenario= without a value",
         "demo.loacity.loa",
         "scenario=",
         ReadResult::ERROR_IN_READING_FILE,
         {"'scenario=' needs a value"}},
        {"missing model",
         dir + "/missing.osgb.loa",
         "",
         ReadResult::FILE_NOT_FOUND,
         {"loa: ", "model '" + dir + "/missing.osgb' not found"}},
        {"no model name",
         dir + "/nothing.loa",
         "",
         ReadResult::FILE_NOT_FOUND,
         {"no .loa file", "nothing.loa"}},
        {"inner reader's error",
         "demo.loacity.loa",
         "blocksX=0",
         ReadResult::ERROR_IN_READING_FILE,
         {"demo.loacity", "blocksX"}},
    };
    for (const Case& c : cases)
    {
        ReadResult rr = read(c.file, c.options);
        EXPECT_FALSE(rr.validNode()) << c.what;
        EXPECT_EQ(rr.status(), c.status) << c.what << ": " << rr.statusMessage();
        for (const std::string& part : c.messageParts)
            EXPECT_NE(rr.message().find(part), std::string::npos) << c.what << ": " << rr.message();
    }
}

TEST(LoaPluginTest, LoaFileErrorsNameTheFileAndTheProblem)
{
    const std::string dir = loatest::freshDirectory("LoaPluginTest-loa-errors");
    writeBox(dir);
    struct Case
    {
        const char* name;
        const char* text;
        ReadResult::ReadStatus status;
        std::vector<std::string> messageParts;
    };
    const Case cases[] = {
        {"malformed.loa",
         "{\"models\": [\"box.osgt\"",
         ReadResult::ERROR_IN_READING_FILE,
         {"not valid JSON"}},
        {"array.loa", "[\"box.osgt\"]", ReadResult::ERROR_IN_READING_FILE, {"expected a JSON object"}},
        {"no-models.loa", "{\"scenario\": \"route\"}", ReadResult::ERROR_IN_READING_FILE, {"no 'models'"}},
        {"empty-models.loa", "{\"models\": []}", ReadResult::ERROR_IN_READING_FILE, {"'models' is empty"}},
        {"number-model.loa", "{\"models\": [3]}", ReadResult::ERROR_IN_READING_FILE, {"'models' must list"}},
        {"unknown-key.loa",
         "{\"models\": [\"box.osgt\"], \"senario\": \"route\"}",
         ReadResult::ERROR_IN_READING_FILE,
         {"unknown key 'senario'"}},
        {"bad-scenario-type.loa",
         "{\"models\": [\"box.osgt\"], \"scenario\": 1}",
         ReadResult::ERROR_IN_READING_FILE,
         {"'scenario' must be a non-empty string"}},
        {"unknown-scenario.loa",
         "{\"models\": [\"box.osgt\"], \"scenario\": \"no-such-scenario\"}",
         ReadResult::ERROR_IN_READING_FILE,
         {"no scenario named 'no-such-scenario'"}},
        {"missing-scenario-file.loa",
         "{\"models\": [\"box.osgt\"], \"scenario\": \"nope.osgt\"}",
         ReadResult::ERROR_IN_READING_FILE,
         {"nope.osgt", "not found"}},
        {"missing-model.loa",
         "{\"models\": [\"box.osgt\", \"trees.osgb\"]}",
         ReadResult::FILE_NOT_FOUND,
         {"model '" + dir + "/trees.osgb' not found"}},
    };
    for (const Case& c : cases)
    {
        const std::string path = dir + "/" + c.name;
        writeText(path, c.text);
        ReadResult rr = read(path);
        EXPECT_FALSE(rr.validNode()) << c.name;
        EXPECT_EQ(rr.status(), c.status) << c.name << ": " << rr.statusMessage();
        EXPECT_NE(rr.message().find("loa: '" + path + "': "), std::string::npos)
            << c.name << ": " << rr.message();
        for (const std::string& part : c.messageParts)
            EXPECT_NE(rr.message().find(part), std::string::npos) << c.name << ": " << rr.message();
    }
}

TEST(LoaPluginTest, LoaFileWithTwoModelsAScenarioFileAndOptions)
{
    const std::string dir = loatest::freshDirectory("LoaPluginTest-two");
    writeBox(dir);
    osg::ref_ptr<osgLoA::UsageScenario> s = osgLoA::ScenarioLibrary::createBuiltin("circular-roi");
    s->setName("local-roi");
    osgLoA::ScenarioLibrary::writeFile(*s, dir + "/local.osgt");
    // Paths are relative to the .loa file, comments are allowed, "options" go to the readers.
    writeText(dir + "/two.loa", R"(// a city and a box
{
  "description": "two models, one scenario",
  "models": ["demo.loacity", "box.osgt"],
  "scenario": "local.osgt",   /* next to this file */
  "options": ")" + kCity + R"("
})");
    ScopedCapture capture;
    osg::ref_ptr<osgLoA::LoANode> loa = readLoa(dir + "/two.loa");
    ASSERT_TRUE(loa.valid());
    EXPECT_EQ(loa->getNumChildren(), 2u);
    EXPECT_EQ(loa->getScenario()->getName(), "local-roi");
    osgLoA::FeatureIndex index(*loa);
    EXPECT_TRUE(index.duplicateIds().empty());
    // The box's new feature is numbered after the city's.
    unsigned cityMax = 0, boxId = 0;
    for (const auto& e : index.entries())
    {
        if (e.node->getName() == "box")
            boxId = e.feature->getId();
        else
            cityMax = std::max(cityMax, e.feature->getId());
    }
    EXPECT_GT(boxId, cityMax);
    EXPECT_EQ(capture.text().find("loa:"), std::string::npos) << capture.text();

    // The option string overrides the file's scenario.
    osg::ref_ptr<osgLoA::LoANode> route = readLoa(dir + "/two.loa", "scenario=route");
    ASSERT_TRUE(route.valid());
    EXPECT_EQ(route->getScenario()->getName(), "route");
}

TEST(LoaPluginTest, FeatureIdsInSeveralModelsAreReported)
{
    const std::string dir = loatest::freshDirectory("LoaPluginTest-duplicates");
    // Two copies of one city: every feature id twice.
    writeText(dir + "/twice.loa", R"({"models": ["a.loacity", "b.loacity"], "options": ")" + kCity + R"("})");
    ScopedCapture capture;
    osg::ref_ptr<osgLoA::LoANode> loa = readLoa(dir + "/twice.loa");
    ASSERT_TRUE(loa.valid());
    EXPECT_EQ(loa->getNumChildren(), 2u);
    EXPECT_NE(capture.text().find("feature ids occur in more than one place"), std::string::npos)
        << capture.text();
}

TEST(LoaPluginTest, TheDemoLoaFileLoadsTheCityWithTheRouteScenario)
{
    const std::string path = std::string(LOA_SOURCE_DIR) + "/data/demo.loa";
    // The full default city; its options could be made small with -O, but this is the file as
    // users open it.
    osg::ref_ptr<osgLoA::LoANode> loa = readLoa(path);
    ASSERT_TRUE(loa.valid());
    EXPECT_EQ(loa->getScenario()->getName(), "route");
    EXPECT_GT(osgLoA::FeatureIndex(*loa).counts().get(osgLoA::FeatureType::Building), 100u);
}

TEST(LoaPluginTest, SavedLoaNodesKeepTheirScenarioAndDoNotNest)
{
    const std::string dir = loatest::freshDirectory("LoaPluginTest-saved");
    osg::ref_ptr<osgLoA::LoANode> loa = readLoa("demo.loacity.loa", "scenario=view-angle " + kCity);
    ASSERT_TRUE(loa.valid());
    ASSERT_TRUE(osgDB::writeNodeFile(*loa, dir + "/city.osgb"));

    osg::ref_ptr<osgLoA::LoANode> again = readLoa(dir + "/city.osgb.loa");
    ASSERT_TRUE(again.valid());
    EXPECT_EQ(again->getScenario()->getName(), "view-angle");
    ASSERT_EQ(again->getNumChildren(), 1u);
    EXPECT_EQ(dynamic_cast<osgLoA::LoANode*>(again->getChild(0)), nullptr);

    osg::ref_ptr<osgLoA::LoANode> routed = readLoa(dir + "/city.osgb.loa", "scenario=route");
    ASSERT_TRUE(routed.valid());
    EXPECT_EQ(routed->getScenario()->getName(), "route");
}

// The library files hold an empty LoA node carrying the scenario (ScenarioLibrary::writeFile),
// so the stock osgconv converts them (OSG 3.6.5's osgconv crashes on a file without a node):
// .osgt -> .osgb -> .osgt gives the library file back byte for byte.
TEST(LoaPluginTest, OsgconvRoundTripOfEveryLibraryScenario)
{
    if (!haveOsgconv()) GTEST_SKIP() << "osgconv not installed (Debian package openscenegraph)";
    const std::string dir = loatest::freshDirectory("LoaPluginTest-osgconv");
    const std::string library = std::string(LOA_SOURCE_DIR) + "/data/scenarios";
    std::vector<std::string> names;
    for (const std::string& f : osgDB::getDirectoryContents(library))
        if (osgDB::getLowerCaseFileExtension(f) == "osgt") names.push_back(f);
    ASSERT_EQ(names.size(), osgLoA::ScenarioLibrary::builtinNames().size());
    for (const std::string& f : names)
    {
        const std::string original = library + "/" + f, binary = dir + "/" + f + ".osgb",
                          back = dir + "/" + f + ".back.osgt";
        int rc = 0;
        std::string out = osgconv(quote(original) + " " + quote(binary), rc);
        ASSERT_EQ(rc, 0) << f << ":\n" << out;
        out = osgconv(quote(binary) + " " + quote(back), rc);
        ASSERT_EQ(rc, 0) << f << ":\n" << out;
        EXPECT_EQ(textOf(back), textOf(original)) << f << ": osgconv's round trip changed the file";
        // And the binary file is a scenario the library reads.
        EXPECT_EQ(scenarioText(*osgLoA::ScenarioLibrary::readFile(binary), dir), textOf(original)) << f;
    }
}

TEST(LoaPluginTest, OsgconvKeepsTheLoaNodeOfTheDemoCity)
{
    if (!haveOsgconv()) GTEST_SKIP() << "osgconv not installed (Debian package openscenegraph)";
    const std::string dir = loatest::freshDirectory("LoaPluginTest-osgconv-city");
    int rc = 0;
    const std::string out = osgconv(
        "-O " + quote("scenario=route " + kCity) + " demo.loacity.loa " + quote(dir + "/city.osgb"), rc);
    ASSERT_EQ(rc, 0) << out;
    osg::ref_ptr<osg::Node> node = osgDB::readRefNodeFile(dir + "/city.osgb");
    osg::ref_ptr<osgLoA::LoANode> loa = dynamic_cast<osgLoA::LoANode*>(node.get());
    ASSERT_TRUE(loa.valid()) << "osgconv's output is not a LoANode";
    ASSERT_NE(loa->getScenario(), nullptr);
    EXPECT_EQ(loa->getScenario()->getName(), "route");
    EXPECT_EQ(scenarioText(*loa->getScenario(), dir),
              scenarioText(*osgLoA::ScenarioLibrary::load("route"), dir));

    // osgconv's optimizer keeps every feature and its type.
    osg::ref_ptr<osgLoA::LoANode> direct = readLoa("demo.loacity.loa", "scenario=route " + kCity);
    ASSERT_TRUE(direct.valid());
    const auto expected = osgLoA::FeatureIndex(*direct).counts(),
               counts = osgLoA::FeatureIndex(*loa).counts();
    EXPECT_EQ(counts.total, expected.total);
    for (osgLoA::FeatureType t : osgLoA::kFeatureTypes)
        EXPECT_EQ(counts.get(t), expected.get(t)) << osgLoA::toString(t);
}
