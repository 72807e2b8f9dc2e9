// Colour schemes per sub-type (paper 004 §3.2.3, Brewer 1994; osgLoA::ColorScheme): the built-in
// schemes, their uniform array against the FeatureSubType codes, the CPU twin of the shader's
// colour choice, a scenario's scheme validated, and loa-scenario's colors= key.
#include "support/TestSupport.h"

#include <osgLoA/semantics/FeatureSubType>
#include <osgLoA/styles/ColorScheme>
#include <osgLoA/transitions/ScenarioLibrary>
#include <osgLoA/transitions/UsageScenario>

#include <gtest/gtest.h>

#include <string>

using namespace osgLoA;

TEST(ColorSchemeTest, BuiltinSchemes)
{
    EXPECT_EQ(ColorScheme::names(), "feature-types, brewer-subtypes");
    ASSERT_NE(ColorScheme::find("feature-types"), nullptr);
    EXPECT_TRUE(ColorScheme::find("feature-types")->colors.empty());
    const ColorScheme::Scheme* b = ColorScheme::find("brewer-subtypes");
    ASSERT_NE(b, nullptr);
    EXPECT_EQ(ColorScheme::find("Brewer-Subtypes"), nullptr); // names are case-sensitive
    // Every word of the scheme is a sub-type the table knows (a typo would colour nothing).
    for (const auto& entry : b->colors)
        EXPECT_GT(FeatureSubType::code(entry.subType), 0) << entry.subType;
}

TEST(ColorSchemeTest, UniformHoldsTheSchemeByCode)
{
    const ColorScheme::Scheme& b = *ColorScheme::find("brewer-subtypes");
    osg::ref_ptr<osg::Uniform> u = ColorScheme::uniform(b);
    EXPECT_EQ(u->getName(), std::string(ColorScheme::kUniform));
    EXPECT_EQ(u->getNumElements(), unsigned(FeatureSubType::kCount));
    osg::Vec4f v;
    // coniferous (code 2): Paired dark green #33a02c, for green spaces (a = 1 + 4); major (32):
    // Set3 orange #fdb462, for streets (1 + 2); landmark (44): Set3 purple #bc80bd, for buildings
    // (1 + 1); tree (23): not coloured.
    u->getElement(2, v);
    EXPECT_EQ(v, osg::Vec4f(51 / 255.0f, 160 / 255.0f, 44 / 255.0f, 5.0f));
    u->getElement(32, v);
    EXPECT_EQ(v, osg::Vec4f(253 / 255.0f, 180 / 255.0f, 98 / 255.0f, 3.0f));
    u->getElement(44, v);
    EXPECT_EQ(v, osg::Vec4f(188 / 255.0f, 128 / 255.0f, 189 / 255.0f, 2.0f));
    u->getElement(23, v);
    EXPECT_EQ(v.a(), 0.0f);
    u->getElement(0, v);
    EXPECT_EQ(v.a(), 0.0f);
    // feature-types colours nothing.
    osg::ref_ptr<osg::Uniform> none = ColorScheme::uniform(*ColorScheme::find("feature-types"));
    for (unsigned i = 0; i < none->getNumElements(); ++i)
    {
        none->getElement(i, v);
        EXPECT_EQ(v.a(), 0.0f);
    }
    // The twin: a sub-type's colour where the scheme has one, else the type's.
    const osg::Vec3f type(0.5f, 0.5f, 0.5f);
    EXPECT_EQ(ColorScheme::colorOf(b, FeatureType::Green, "Coniferous", type),
              osg::Vec3f(51, 160, 44) / 255.0f);
    EXPECT_EQ(ColorScheme::colorOf(b, FeatureType::Green, "tree", type), type);
    EXPECT_EQ(ColorScheme::colorOf(b, FeatureType::Green, "", type), type);
    EXPECT_EQ(ColorScheme::colorOf(b, FeatureType::Green, "no-such-kind", type), type);
    // A word of two types: "residential" is coloured for buildings, not for a street so named.
    EXPECT_EQ(ColorScheme::colorOf(b, FeatureType::Building, "residential", type),
              osg::Vec3f(251, 128, 114) / 255.0f);
    EXPECT_EQ(ColorScheme::colorOf(b, FeatureType::Street, "residential", type), type);
}

TEST(ColorSchemeTest, ScenarioSchemeIsValidated)
{
    osg::ref_ptr<UsageScenario> s = ScenarioLibrary::createHomogeneous("cartographic");
    EXPECT_TRUE(s->validate().ok());
    s->setColorScheme("brewer-subtypes");
    EXPECT_TRUE(s->validate().ok());
    s->setColorScheme("rainbow");
    const UsageScenario::Validation v = s->validate();
    ASSERT_FALSE(v.ok());
    EXPECT_NE(v.errors.front().find("colour scheme 'rainbow' is not one of feature-types, brewer-subtypes"),
              std::string::npos)
        << v.errors.front();
}

TEST(ColorSchemeTest, LoaScenarioSetsTheScheme)
{
    const std::string dir = loatest::freshDirectory("ColorSchemeTest");
    const std::string file = dir + "/map.osgt";
    std::string out;
    ASSERT_EQ(loatest::run(std::string(LOA_SCENARIO_EXE) + " create " + file, out), 0) << out;
    ASSERT_EQ(loatest::run(std::string(LOA_SCENARIO_EXE) + " set " + file + " colors=brewer-subtypes", out),
              0)
        << out;
    ASSERT_EQ(loatest::run(std::string(LOA_SCENARIO_EXE) + " show " + file, out), 0) << out;
    EXPECT_NE(out.find("colour scheme: brewer-subtypes"), std::string::npos) << out;
    const std::string before = loatest::fileBytes(file);
    EXPECT_NE(loatest::run(std::string(LOA_SCENARIO_EXE) + " set " + file + " colors=rainbow", out), 0);
    EXPECT_NE(out.find("colors=rainbow: not a colour scheme (feature-types, brewer-subtypes, or none)"),
              std::string::npos)
        << out;
    EXPECT_EQ(loatest::fileBytes(file), before); // unchanged
    ASSERT_EQ(loatest::run(std::string(LOA_SCENARIO_EXE) + " set " + file + " colors=none", out), 0) << out;
    ASSERT_EQ(loatest::run(std::string(LOA_SCENARIO_EXE) + " show " + file, out), 0) << out;
    EXPECT_NE(out.find("colour scheme: none"), std::string::npos) << out;
}
