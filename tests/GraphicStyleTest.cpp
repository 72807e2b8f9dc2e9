// Graphic styles (paper 004 §3.2.3): the built-in styles' defaults, their serialization
// (write-read-write round trips in .osgt and .osgb), the catalog that resolves names, program
// creation, and the abstract style's colour quantization on the CPU (ColorQuantization).
#include "support/TestSupport.h"

#include <osgLoA/styles/ColorQuantization>
#include <osgLoA/styles/GraphicStyle>
#include <osgLoA/styles/GraphicStyleCatalog>
#include <osgLoA/styles/ObjectSpaceEdges>

#include <osg/Geometry>
#include <osg/Uniform>
#include <osgDB/ReadFile>
#include <osgDB/Registry>
#include <osgDB/WriteFile>

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <thread>

using namespace osgLoA;

namespace
{
std::string fileBytes(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

/** Writes style to dir/NAME-first.EXT, reads it, writes that to NAME-second.EXT; the two files
 *  must be the same bytes. Returns the style read. */
osg::ref_ptr<GraphicStyle> roundTrip(const GraphicStyle& style, const std::string& dir,
                                     const std::string& ext)
{
    const std::string first = dir + "/" + style.getName() + "-first." + ext;
    const std::string second = dir + "/" + style.getName() + "-second." + ext;
    EXPECT_TRUE(osgDB::writeObjectFile(style, first)) << first;
    osg::ref_ptr<GraphicStyle> back = dynamic_cast<GraphicStyle*>(osgDB::readRefObjectFile(first).get());
    EXPECT_TRUE(back.valid()) << first << " did not read back as a GraphicStyle";
    if (!back) return back;
    EXPECT_TRUE(osgDB::writeObjectFile(*back, second)) << second;
    const std::string a = fileBytes(first), b = fileBytes(second);
    EXPECT_FALSE(a.empty());
    EXPECT_TRUE(a == b) << style.getName() << "." << ext << ": the second write differs\n--- first\n"
                        << (ext == "osgb" ? std::string("(binary)") : a) << "\n--- second\n"
                        << (ext == "osgb" ? std::string("(binary)") : b);
    return back;
}

float floatParameter(const GraphicStyle& s, const std::string& name)
{
    const osg::Uniform* u = s.getParameter(name);
    float v = -1.0f;
    EXPECT_TRUE(u && u->get(v)) << s.getName() << ": " << name;
    return v;
}

void expectSameStyle(const GraphicStyle& a, const GraphicStyle& b)
{
    EXPECT_EQ(a.getName(), b.getName());
    EXPECT_EQ(a.getDescription(), b.getDescription());
    EXPECT_EQ(a.getFragmentShader(), b.getFragmentShader());
    EXPECT_EQ(a.getVisible(), b.getVisible());
    EXPECT_EQ(a.getOpaque(), b.getOpaque());
    EXPECT_EQ(a.getUsesTexture(), b.getUsesTexture());
    EXPECT_EQ(a.getEdgeColor(), b.getEdgeColor());
    EXPECT_FLOAT_EQ(a.getEdgeStrength(), b.getEdgeStrength());
    EXPECT_FLOAT_EQ(a.getUnsharpMaskStrength(), b.getUnsharpMaskStrength());
    EXPECT_FLOAT_EQ(a.getUnsharpMaskRadius(), b.getUnsharpMaskRadius());
    ASSERT_TRUE(a.getParameters() && b.getParameters());
    const auto& ua = a.getParameters()->getUniformList();
    const auto& ub = b.getParameters()->getUniformList();
    ASSERT_EQ(ua.size(), ub.size()) << a.getName();
    for (const auto& entry : ua)
    {
        const osg::Uniform* x = entry.second.first.get();
        const osg::Uniform* y = b.getParameters()->getUniform(entry.first);
        ASSERT_TRUE(y) << a.getName() << ": " << entry.first << " lost";
        EXPECT_EQ(x->getType(), y->getType()) << entry.first;
        EXPECT_EQ(x->getNumElements(), y->getNumElements()) << entry.first;
        if (x->getFloatArray() && y->getFloatArray())
        {
            ASSERT_EQ(x->getFloatArray()->size(), y->getFloatArray()->size());
            for (unsigned i = 0; i < x->getFloatArray()->size(); ++i)
                EXPECT_NEAR((*x->getFloatArray())[i], (*y->getFloatArray())[i], 1e-6f) << entry.first;
        }
        if (x->getIntArray() && y->getIntArray())
        {
            ASSERT_EQ(x->getIntArray()->size(), y->getIntArray()->size());
            for (unsigned i = 0; i < x->getIntArray()->size(); ++i)
                EXPECT_EQ((*x->getIntArray())[i], (*y->getIntArray())[i]) << entry.first;
        }
    }
}

osg::Vec3f chromaOf(const osg::Vec3f& srgb)
{
    return ColorQuantization::srgbToOklab(srgb);
}
} // namespace

// --- built-in styles -----------------------------------------------------------------------

TEST(GraphicStyleTest, BuiltinsHaveTheirNamesShadersAndHints)
{
    const std::vector<std::string> expected = {"photorealistic", "abstract", "cartographic", "blueprint",
                                               "hidden"};
    EXPECT_EQ(GraphicStyle::builtinNames(), expected);
    for (const std::string& name : expected)
    {
        osg::ref_ptr<GraphicStyle> s = GraphicStyle::createBuiltin(name);
        ASSERT_TRUE(s.valid()) << name;
        EXPECT_EQ(s->getName(), name);
        EXPECT_FALSE(s->getDescription().empty()) << name;
        ASSERT_TRUE(s->getParameters()) << name;
        if (name == "hidden")
        {
            EXPECT_FALSE(s->getVisible());
            EXPECT_TRUE(s->getFragmentShader().empty());
        }
        else
        {
            EXPECT_TRUE(s->getVisible()) << name;
            EXPECT_TRUE(s->getOpaque()) << name;
            EXPECT_EQ(s->getFragmentShader(), "loa_style_" + name + ".frag.glsl");
        }
    }
    // Each call makes a new instance with its own parameters.
    osg::ref_ptr<GraphicStyle> a = GraphicStyle::createBuiltin("cartographic");
    osg::ref_ptr<GraphicStyle> b = GraphicStyle::createBuiltin("cartographic");
    EXPECT_NE(a->getParameters(), b->getParameters());
    EXPECT_NE(a->getParameter("loa_cartographic_colors"), b->getParameter("loa_cartographic_colors"));
}

TEST(GraphicStyleTest, ParameterDefaults)
{
    osg::ref_ptr<GraphicStyle> photo = GraphicStyle::createBuiltin("photorealistic");
    EXPECT_FLOAT_EQ(floatParameter(*photo, "loa_photorealistic_ambient"), 0.35f);
    bool materialDiffuse = true;
    ASSERT_TRUE(photo->getParameter("loa_photorealistic_materialDiffuse"));
    EXPECT_TRUE(photo->getParameter("loa_photorealistic_materialDiffuse")->get(materialDiffuse));
    EXPECT_FALSE(materialDiffuse);
    EXPECT_TRUE(photo->getUsesTexture());
    EXPECT_EQ(photo->getEdgeStrength(), 0.0f);
    EXPECT_EQ(photo->getUnsharpMaskStrength(), 0.0f);

    osg::ref_ptr<GraphicStyle> abstract = GraphicStyle::createBuiltin("abstract");
    int levels = 0;
    ASSERT_TRUE(abstract->getParameter("loa_abstract_levels"));
    EXPECT_TRUE(abstract->getParameter("loa_abstract_levels")->get(levels));
    EXPECT_GE(levels, 4);
    EXPECT_LE(levels, 6);
    EXPECT_FLOAT_EQ(floatParameter(*abstract, "loa_abstract_chromaStep"), 0.05f);
    EXPECT_FLOAT_EQ(floatParameter(*abstract, "loa_abstract_ambient"), 0.6f);
    EXPECT_TRUE(abstract->getUsesTexture());
    EXPECT_GT(abstract->getEdgeStrength(), 0.0f);
    EXPECT_LT(abstract->getEdgeStrength(), 0.5f); // light edges

    osg::ref_ptr<GraphicStyle> carto = GraphicStyle::createBuiltin("cartographic");
    EXPECT_FALSE(carto->getUsesTexture());
    EXPECT_NEAR(carto->getEdgeStrength(), 0.8f, 1e-6f);
    EXPECT_LT(carto->getEdgeColor().length(), 0.5f); // dark edges
    EXPECT_GT(carto->getUnsharpMaskStrength(), 0.0f);
    EXPECT_GT(carto->getUnsharpMaskRadius(), 0.0f);
    EXPECT_FLOAT_EQ(floatParameter(*carto, "loa_cartographic_ambient"), 0.6f);
    const osg::Uniform* colors = carto->getParameter("loa_cartographic_colors");
    ASSERT_TRUE(colors);
    EXPECT_EQ(colors->getType(), osg::Uniform::FLOAT_VEC3);
    ASSERT_EQ(colors->getNumElements(), 6u);
    for (unsigned i = 0; i < 6; ++i)
    {
        osg::Vec3f c;
        EXPECT_TRUE(colors->getElement(i, c));
        EXPECT_EQ(c, GraphicStyle::cartographicColors()[i]) << i;
    }

    osg::ref_ptr<GraphicStyle> blue = GraphicStyle::createBuiltin("blueprint");
    EXPECT_EQ(blue->getEdgeColor(), osg::Vec3f(1, 1, 1));
    EXPECT_EQ(blue->getEdgeStrength(), 1.0f);
    EXPECT_FALSE(blue->getUsesTexture());
    osg::Vec3f ground;
    ASSERT_TRUE(blue->getParameter("loa_blueprint_color"));
    EXPECT_TRUE(blue->getParameter("loa_blueprint_color")->get(ground));
    EXPECT_GT(ground.z(), ground.x() + 0.2f); // blue
    EXPECT_GT(ground.z(), ground.y() + 0.1f);
    EXPECT_FLOAT_EQ(floatParameter(*blue, "loa_blueprint_ambient"), 0.8f);
    EXPECT_EQ(blue->getEdge(), osg::Vec4f(1, 1, 1, 1));

    osg::ref_ptr<GraphicStyle> hidden = GraphicStyle::createBuiltin("hidden");
    EXPECT_FALSE(hidden->getVisible());
    EXPECT_FALSE(hidden->getOpaque());
}

TEST(GraphicStyleTest, BrewerColoursAreDistinctPerTypeAndFitMapSemantics)
{
    const auto& c = GraphicStyle::cartographicColors();
    for (unsigned i = 0; i < c.size(); ++i)
        for (unsigned j = i + 1; j < c.size(); ++j)
            EXPECT_GT((c[i] - c[j]).length(), 0.1f)
                << toString(FeatureType(i)) << " vs " << toString(FeatureType(j));
    const osg::Vec3f water = GraphicStyle::cartographicColor(FeatureType::Water);
    const osg::Vec3f green = GraphicStyle::cartographicColor(FeatureType::Green);
    const osg::Vec3f street = GraphicStyle::cartographicColor(FeatureType::Street);
    EXPECT_GT(water.z(), water.x());
    EXPECT_GT(water.z(), water.y());
    EXPECT_GT(green.y(), green.x());
    EXPECT_GT(green.y(), green.z());
    EXPECT_GT(street.x() + street.y() + street.z(), 2.4f); // light
    EXPECT_GE(street.x(), street.z());                     // warm
    // Set3 #80b1d3 for water, exactly.
    EXPECT_EQ(water, osg::Vec3f(128 / 255.0f, 177 / 255.0f, 211 / 255.0f));
    for (FeatureType t : kFeatureTypes)
        EXPECT_EQ(GraphicStyle::cartographicColor(t), c[static_cast<int>(t)]);
}

TEST(GraphicStyleTest, UnknownNamesAreRejected)
{
    EXPECT_THROW(GraphicStyle::createBuiltin("watercolour"), std::invalid_argument);
    EXPECT_THROW(GraphicStyle::createBuiltin(""), std::invalid_argument);
    EXPECT_THROW(GraphicStyle::createBuiltin("Cartographic"), std::invalid_argument);
    GraphicStyleCatalog& catalog = GraphicStyleCatalog::instance();
    EXPECT_FALSE(catalog.contains("watercolour"));
    EXPECT_FALSE(catalog.prototype("watercolour").valid());
    EXPECT_THROW(catalog.create("watercolour"), std::invalid_argument);
    EXPECT_THROW(catalog.add("two words", "x"), std::invalid_argument);
    osg::ref_ptr<GraphicStyle> unnamed = new GraphicStyle;
    EXPECT_THROW(catalog.add(*unnamed), std::invalid_argument);
}

TEST(GraphicStyleTest, SettersCheckTheirValues)
{
    osg::ref_ptr<GraphicStyle> s = new GraphicStyle;
    EXPECT_TRUE(s->getVisible());
    EXPECT_FALSE(s->getOpaque());
    EXPECT_TRUE(s->getUsesTexture());
    EXPECT_TRUE(s->getParameters());
    s->setEdgeStrength(1.5f);
    EXPECT_EQ(s->getEdgeStrength(), 1.0f);
    s->setEdgeStrength(std::nanf(""));
    EXPECT_EQ(s->getEdgeStrength(), 0.0f);
    s->setEdgeColor(osg::Vec3f(-1.0f, 0.5f, 2.0f));
    EXPECT_EQ(s->getEdgeColor(), osg::Vec3f(0.0f, 0.5f, 1.0f));
    s->setUnsharpMaskStrength(-2.0f);
    EXPECT_EQ(s->getUnsharpMaskStrength(), 0.0f);
    s->setUnsharpMaskRadius(std::nanf(""));
    EXPECT_EQ(s->getUnsharpMaskRadius(), 8.0f);
    s->setParameters(nullptr);
    EXPECT_TRUE(s->getParameters());
    EXPECT_THROW(s->setFragmentShader("loa_style_x.vert.glsl"), std::invalid_argument);
    EXPECT_THROW(s->setFragmentShader("dir/loa_style_x.frag.glsl"), std::invalid_argument);
    EXPECT_THROW(s->setFragmentShader("loa_style_x"), std::invalid_argument);
    s->setFragmentShader("my_style.frag.glsl");
    EXPECT_EQ(s->getFragmentShader(), "my_style.frag.glsl");
}

TEST(GraphicStyleTest, CopiesShareOrCopyTheParameters)
{
    osg::ref_ptr<GraphicStyle> s = GraphicStyle::createBuiltin("abstract");
    osg::ref_ptr<GraphicStyle> shallow = new GraphicStyle(*s);
    EXPECT_EQ(shallow->getParameters(), s->getParameters());
    osg::ref_ptr<GraphicStyle> deep = new GraphicStyle(*s, osg::CopyOp::DEEP_COPY_ALL);
    EXPECT_NE(deep->getParameters(), s->getParameters());
    EXPECT_NE(deep->getParameter("loa_abstract_levels"), s->getParameter("loa_abstract_levels"));
    expectSameStyle(*s, *deep);
    osg::ref_ptr<osg::Object> cloned = s->clone(osg::CopyOp::DEEP_COPY_ALL);
    ASSERT_TRUE(dynamic_cast<GraphicStyle*>(cloned.get()));
    expectSameStyle(*s, *static_cast<GraphicStyle*>(cloned.get()));
}

TEST(GraphicStyleTest, ApplyParametersMergesTheUniformsIntoAStateSet)
{
    osg::ref_ptr<GraphicStyle> s = GraphicStyle::createBuiltin("cartographic");
    osg::ref_ptr<osg::StateSet> ss = new osg::StateSet;
    ss->addUniform(new osg::Uniform("loa_featureType", 3));
    s->applyParameters(*ss);
    EXPECT_TRUE(ss->getUniform("loa_featureType"));
    EXPECT_EQ(ss->getUniform("loa_cartographic_colors"), s->getParameter("loa_cartographic_colors"));
    EXPECT_TRUE(ss->getUniform("loa_cartographic_ambient"));
}

// --- programs ----------------------------------------------------------------------------------

TEST(GraphicStyleTest, CreateProgramLinksTheCommonShadersAndTheStyleFragment)
{
    loatest::setFilePath("");
    const std::vector<std::string> common = {"loa_plain.vert.glsl", "loa_transition.frag.glsl"};
    for (const std::string& name : GraphicStyle::builtinNames())
    {
        osg::ref_ptr<GraphicStyle> s = GraphicStyle::createBuiltin(name);
        if (!s->getVisible())
        {
            EXPECT_THROW(s->createProgram(common), std::logic_error) << name;
            continue;
        }
        const std::vector<std::string> names = s->shaderNames(common);
        // The common shaders, the fixed-function library the built-in styles call, the style's.
        ASSERT_EQ(names.size(), 4u);
        EXPECT_EQ(names[2], "loa_fixed_function.frag.glsl");
        EXPECT_EQ(names.back(), s->getFragmentShader());
        osg::ref_ptr<osg::Program> p = s->createProgram(common);
        ASSERT_TRUE(p.valid()) << name;
        EXPECT_EQ(p->getName(), "loa_style_" + name);
        ASSERT_EQ(p->getNumShaders(), 4u);
        EXPECT_EQ(p->getShader(0)->getName(), "loa_plain.vert.glsl");
        EXPECT_EQ(p->getShader(1)->getName(), "loa_transition.frag.glsl");
        EXPECT_EQ(p->getShader(2)->getName(), "loa_fixed_function.frag.glsl");
        EXPECT_EQ(p->getShader(3)->getName(), s->getFragmentShader());
        EXPECT_EQ(p->getShader(3)->getType(), osg::Shader::FRAGMENT);
        EXPECT_NE(p->getShader(3)->getShaderSource().find("loa_styleColor"), std::string::npos) << name;
    }
    osg::ref_ptr<GraphicStyle> missing = new GraphicStyle;
    missing->setName("missing");
    EXPECT_THROW(missing->createProgram(common), std::logic_error); // no fragment shader
    missing->setFragmentShader("loa_style_missing.frag.glsl");
    EXPECT_THROW(missing->createProgram(common), std::invalid_argument);
}

TEST(GraphicStyleTest, AStyleShaderIsOverriddenThroughOsgFilePath)
{
    const std::string dir = loatest::freshDirectory("GraphicStyleOverride");
    const std::string text =
        "#version 450 compatibility\n// my blueprint\nvec4 loa_styleColor(vec3 s, vec3 v, "
        "vec3 n, vec2 t, vec4 c) { return vec4(1.0); }\n";
    std::ofstream(dir + "/loa_style_blueprint.frag.glsl") << text;
    loatest::setFilePath(dir);
    osg::ref_ptr<osg::Program> p =
        GraphicStyle::createBuiltin("blueprint")->createProgram({"loa_plain.vert.glsl"});
    loatest::setFilePath("");
    ASSERT_EQ(p->getNumShaders(), 3u);
    EXPECT_EQ(p->getShader(2)->getShaderSource(), text);
}

// --- catalog -------------------------------------------------------------------------------------

TEST(GraphicStyleTest, TheCatalogResolvesEveryBuiltinName)
{
    GraphicStyleCatalog& catalog = GraphicStyleCatalog::instance();
    const std::vector<std::string> names = catalog.names();
    for (const std::string& name : GraphicStyle::builtinNames())
    {
        EXPECT_TRUE(catalog.contains(name)) << name;
        EXPECT_NE(std::find(names.begin(), names.end(), name), names.end());
        osg::ref_ptr<const GraphicStyle> p = catalog.prototype(name);
        ASSERT_TRUE(p.valid()) << name;
        EXPECT_EQ(p->getName(), name);
        osg::ref_ptr<GraphicStyle> copy = catalog.create(name);
        ASSERT_TRUE(copy.valid());
        EXPECT_NE(copy->getParameters(), p->getParameters());
        expectSameStyle(*p, *copy);
        expectSameStyle(*GraphicStyle::createBuiltin(name), *copy);
    }
    for (const auto& e : catalog.entries())
    {
        ASSERT_TRUE(e.style.valid()) << e.name;
        EXPECT_EQ(e.style->getName(), e.name);
        EXPECT_EQ(e.style->getDescription(), e.description);
    }
    // Editing a copy leaves the prototype alone.
    osg::ref_ptr<GraphicStyle> copy = catalog.create("cartographic");
    copy->getParameter("loa_cartographic_colors")->setElement(3, osg::Vec3f(1, 0, 0));
    copy->setEdgeStrength(0.1f);
    osg::Vec3f water;
    catalog.prototype("cartographic")->getParameter("loa_cartographic_colors")->getElement(3, water);
    EXPECT_EQ(water, GraphicStyle::cartographicColor(FeatureType::Water));
    EXPECT_NEAR(catalog.prototype("cartographic")->getEdgeStrength(), 0.8f, 1e-6f);
}

TEST(GraphicStyleTest, ApplicationsAddTheirOwnStyles)
{
    GraphicStyleCatalog& catalog = GraphicStyleCatalog::instance();
    // The old API: a name and a description; the style's shader follows the name.
    catalog.add("test-sketchy", "pencil strokes");
    ASSERT_TRUE(catalog.contains("test-sketchy"));
    osg::ref_ptr<const GraphicStyle> sketchy = catalog.prototype("test-sketchy");
    ASSERT_TRUE(sketchy.valid());
    EXPECT_EQ(sketchy->getFragmentShader(), "loa_style_test-sketchy.frag.glsl");
    EXPECT_EQ(sketchy->getDescription(), "pencil strokes");
    EXPECT_TRUE(sketchy->getVisible());
    // Re-describing a built-in keeps its style.
    catalog.add("blueprint", "white lines on blue");
    EXPECT_EQ(catalog.prototype("blueprint")->getDescription(), "white lines on blue");
    EXPECT_EQ(catalog.prototype("blueprint")->getEdgeColor(), osg::Vec3f(1, 1, 1));
    catalog.add("blueprint", GraphicStyle::createBuiltin("blueprint")->getDescription());

    // A whole style: the catalog keeps a copy.
    osg::ref_ptr<GraphicStyle> night = GraphicStyle::createBuiltin("blueprint");
    night->setName("test-night");
    night->setDescription("dark blue");
    night->getParameter("loa_blueprint_color")->set(osg::Vec3f(0.0f, 0.0f, 0.2f));
    catalog.add(*night);
    night->getParameter("loa_blueprint_color")->set(osg::Vec3f(1.0f, 0.0f, 0.0f));
    osg::ref_ptr<GraphicStyle> got = catalog.create("test-night");
    osg::Vec3f color;
    got->getParameter("loa_blueprint_color")->get(color);
    EXPECT_EQ(color, osg::Vec3f(0.0f, 0.0f, 0.2f));
    EXPECT_EQ(got->getDescription(), "dark blue");
    const auto entries = catalog.entries();
    EXPECT_EQ(entries.front().name, "photorealistic"); // built-ins first, in order
}

TEST(GraphicStyleTest, TheCatalogIsThreadSafe)
{
    GraphicStyleCatalog& catalog = GraphicStyleCatalog::instance();
    std::atomic<int> failures{0};
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t)
        threads.emplace_back(
            [&, t]
            {
                for (int i = 0; i < 200; ++i)
                {
                    const std::string name =
                        "test-thread-" + std::to_string(t) + "-" + std::to_string(i % 10);
                    catalog.add(name, "x");
                    if (!catalog.contains(name)) ++failures;
                    osg::ref_ptr<GraphicStyle> c = catalog.create("cartographic");
                    if (!c || c->getName() != "cartographic") ++failures;
                    osg::ref_ptr<const GraphicStyle> p = catalog.prototype("abstract");
                    if (!p) ++failures;
                }
            });
    for (auto& th : threads)
        th.join();
    EXPECT_EQ(failures.load(), 0);
}

// --- serialization -------------------------------------------------------------------------------

TEST(GraphicStyleTest, BuiltinsRoundTripInOsgtAndOsgb)
{
    const std::string dir = loatest::freshDirectory("GraphicStyleRoundTrip");
    for (const std::string& name : GraphicStyle::builtinNames())
        for (const char* ext : {"osgt", "osgb"})
        {
            osg::ref_ptr<GraphicStyle> s = GraphicStyle::createBuiltin(name);
            osg::ref_ptr<GraphicStyle> back = roundTrip(*s, dir, ext);
            ASSERT_TRUE(back.valid()) << name << "." << ext;
            expectSameStyle(*s, *back);
        }
}

// The catalog's styles beyond the built-ins (palette, waterlining, ...) too: every style a
// scenario can name is written and read back the same.
TEST(GraphicStyleTest, EveryCatalogStyleRoundTripsInOsgtAndOsgb)
{
    const std::string dir = loatest::freshDirectory("GraphicStyleCatalogRoundTrip");
    const std::vector<std::string> names = GraphicStyleCatalog::instance().names();
    EXPECT_NE(std::find(names.begin(), names.end(), "waterlining"), names.end());
    for (const std::string& name : names)
        for (const char* ext : {"osgt", "osgb"})
        {
            osg::ref_ptr<GraphicStyle> s = GraphicStyleCatalog::instance().create(name);
            osg::ref_ptr<GraphicStyle> back = roundTrip(*s, dir, ext);
            ASSERT_TRUE(back.valid()) << name << "." << ext;
            expectSameStyle(*s, *back);
        }
}

TEST(GraphicStyleTest, EditedStylesRoundTripWithModesAndAttributes)
{
    const std::string dir = loatest::freshDirectory("GraphicStyleEdited");
    osg::ref_ptr<GraphicStyle> s = GraphicStyle::createBuiltin("cartographic");
    s->setName("my-map");
    s->setDescription("A \"quoted\" word, a back\\slash and braces { }.");
    s->setFragmentShader("my_map.frag.glsl");
    s->setEdgeColor(osg::Vec3f(0.25f, 0.5f, 0.75f));
    s->setEdgeStrength(0.5f);
    s->setUnsharpMaskStrength(2.5f);
    s->setUnsharpMaskRadius(12.0f);
    s->setOpaque(false);
    s->setUsesTexture(true);
    s->getParameter("loa_cartographic_colors")->setElement(2, osg::Vec3f(0.125f, 0.25f, 0.5f));
    s->getParameters()->setMode(GL_CULL_FACE, osg::StateAttribute::OFF);
    for (const char* ext : {"osgt", "osgb"})
    {
        osg::ref_ptr<GraphicStyle> back = roundTrip(*s, dir, ext);
        ASSERT_TRUE(back.valid()) << ext;
        expectSameStyle(*s, *back);
        EXPECT_EQ(back->getParameters()->getMode(GL_CULL_FACE), osg::StateAttribute::OFF);
    }
    // An .osgt file names its parameters so that users can edit them.
    const std::string text = fileBytes(dir + "/my-map-first.osgt");
    EXPECT_NE(text.find("osgLoA::GraphicStyle"), std::string::npos);
    EXPECT_NE(text.find("loa_cartographic_colors"), std::string::npos);
    EXPECT_NE(text.find("EdgeStrength 0.5"), std::string::npos);
}

TEST(GraphicStyleTest, BadValuesInAFileFailTheRead)
{
    const std::string dir = loatest::freshDirectory("GraphicStyleBad");
    const std::string good = dir + "/good.osgt";
    ASSERT_TRUE(osgDB::writeObjectFile(*GraphicStyle::createBuiltin("cartographic"), good));
    const std::string text = fileBytes(good);
    ASSERT_TRUE(osgDB::readRefObjectFile(good).valid());
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"EdgeStrength 0.8", "EdgeStrength 1.5"},
        {"EdgeStrength 0.8", "EdgeStrength -0.5"},
        {"UnsharpMaskStrength 1", "UnsharpMaskStrength -1"},
        {"\"loa_style_cartographic.frag.glsl\"", "\"loa_style_cartographic.vert.glsl\""},
        {"\"loa_style_cartographic.frag.glsl\"", "\"../x.frag.glsl\""},
    };
    int i = 0;
    for (const auto& c : cases)
    {
        const std::string path = dir + "/bad" + std::to_string(i++) + ".osgt";
        std::ofstream(path, std::ios::binary) << loatest::replaced(text, c.first, c.second);
        osg::ref_ptr<osg::Object> o = osgDB::readRefObjectFile(path);
        EXPECT_FALSE(o.valid() && dynamic_cast<GraphicStyle*>(o.get())) << c.second << " read without error";
    }
}

// --- colour quantization (the abstract style's CPU twin) ----------------------------------------

TEST(GraphicStyleTest, OklabOfKnownColours)
{
    // White is L = 1 with no chroma, black L = 0; the Oklab matrices invert each other.
    const osg::Vec3f white = ColorQuantization::srgbToOklab(osg::Vec3f(1, 1, 1));
    EXPECT_NEAR(white.x(), 1.0f, 1e-4f);
    EXPECT_NEAR(white.y(), 0.0f, 1e-4f);
    EXPECT_NEAR(white.z(), 0.0f, 1e-4f);
    EXPECT_NEAR(ColorQuantization::srgbToOklab(osg::Vec3f(0, 0, 0)).x(), 0.0f, 1e-6f);
    // sRGB red: L 0.628, a 0.225, b 0.126 (Ottosson's published values).
    const osg::Vec3f red = ColorQuantization::srgbToOklab(osg::Vec3f(1, 0, 0));
    EXPECT_NEAR(red.x(), 0.628f, 2e-3f);
    EXPECT_NEAR(red.y(), 0.225f, 2e-3f);
    EXPECT_NEAR(red.z(), 0.126f, 2e-3f);
    for (float r : {0.0f, 0.2f, 0.5f, 0.9f})
        for (float g : {0.1f, 0.6f, 1.0f})
            for (float b : {0.0f, 0.3f, 0.8f})
            {
                const osg::Vec3f back =
                    ColorQuantization::oklabToSrgb(ColorQuantization::srgbToOklab({r, g, b}));
                EXPECT_NEAR(back.x(), r, 1e-4f);
                EXPECT_NEAR(back.y(), g, 1e-4f);
                EXPECT_NEAR(back.z(), b, 1e-4f);
            }
    EXPECT_NEAR(ColorQuantization::srgbToLinear(0.5f), 0.214041f, 1e-5f);
    EXPECT_NEAR(ColorQuantization::linearToSrgb(0.214041f), 0.5f, 1e-5f);
}

TEST(GraphicStyleTest, QuantizationOfGreysOnHandComputedLevels)
{
    // Grey sRGB 0.5: linear 0.214041, Oklab L = cbrt(0.214041) = 0.59818. With 5 levels
    // (0, 0.25, 0.5, 0.75, 1) it rounds to 0.5: linear 0.125, sRGB 1.055 * 0.125^(1/2.4) - 0.055
    // = 0.38857.
    const osg::Vec3f q = ColorQuantization::quantize(osg::Vec3f(0.5f, 0.5f, 0.5f), 5, 0.05f);
    EXPECT_NEAR(q.x(), 0.38857f, 1e-4f);
    EXPECT_NEAR(q.y(), 0.38857f, 1e-4f);
    EXPECT_NEAR(q.z(), 0.38857f, 1e-4f);
    EXPECT_EQ(ColorQuantization::lightnessLevel(osg::Vec3f(0.5f, 0.5f, 0.5f), 5), 2);
    // Black and white stay.
    EXPECT_NEAR(ColorQuantization::quantize(osg::Vec3f(0, 0, 0), 5, 0.05f).length(), 0.0f, 1e-4f);
    const osg::Vec3f w = ColorQuantization::quantize(osg::Vec3f(1, 1, 1), 5, 0.05f);
    EXPECT_NEAR(w.x(), 1.0f, 1e-4f);
    EXPECT_NEAR(w.z(), 1.0f, 1e-4f);
    // A grey ramp quantizes to exactly `levels` greys.
    for (int levels : {2, 3, 4, 5, 6, 8})
    {
        std::set<int> outputs;
        for (int v = 0; v <= 255; ++v)
        {
            const float g = v / 255.0f;
            const osg::Vec3f o = ColorQuantization::quantize(osg::Vec3f(g, g, g), levels, 0.05f);
            EXPECT_NEAR(o.x(), o.y(), 1e-4f);
            EXPECT_NEAR(o.x(), o.z(), 1e-4f);
            outputs.insert(static_cast<int>(std::lround(o.x() * 1000.0f)));
        }
        EXPECT_EQ(outputs.size(), static_cast<size_t>(levels)) << levels << " levels";
    }
    // Fewer than 2 levels count as 2.
    EXPECT_EQ(ColorQuantization::quantize(osg::Vec3f(0.3f, 0.3f, 0.3f), 0, 0.05f),
              ColorQuantization::quantize(osg::Vec3f(0.3f, 0.3f, 0.3f), 2, 0.05f));
}

TEST(GraphicStyleTest, QuantizationIsIdempotentKeepsHueAndReducesChroma)
{
    int checked = 0;
    for (int r = 0; r <= 255; r += 17)
        for (int g = 0; g <= 255; g += 17)
            for (int b = 0; b <= 255; b += 17)
            {
                const osg::Vec3f c(r / 255.0f, g / 255.0f, b / 255.0f);
                const osg::Vec3f q = ColorQuantization::quantize(c, 5, 0.05f);
                const osg::Vec3f qq = ColorQuantization::quantize(q, 5, 0.05f);
                ASSERT_NEAR((q - qq).length(), 0.0f, 1.0f / 255.0f) << r << " " << g << " " << b;
                for (int i = 0; i < 3; ++i)
                {
                    EXPECT_GE(q[i], 0.0f);
                    EXPECT_LE(q[i], 1.0f);
                }
                const osg::Vec3f lab = chromaOf(c), qlab = chromaOf(q);
                const float chroma = std::hypot(lab.y(), lab.z()), qchroma = std::hypot(qlab.y(), qlab.z());
                EXPECT_LE(qchroma, chroma + 1e-3f) << r << " " << g << " " << b;
                // On one of the levels (a quantized colour is in gamut, so L is exact).
                EXPECT_NEAR(qlab.x() * 4.0f, std::round(qlab.x() * 4.0f), 1e-3f);
                // Chroma a multiple of the step; the hue kept where there is chroma left.
                EXPECT_NEAR(qchroma / 0.05f, std::round(qchroma / 0.05f), 2e-2f) << r << " " << g << " " << b;
                if (qchroma > 0.02f)
                {
                    const float cosAngle = (lab.y() * qlab.y() + lab.z() * qlab.z()) / (chroma * qchroma);
                    EXPECT_GT(cosAngle, 0.999f) << r << " " << g << " " << b;
                }
                ++checked;
            }
    EXPECT_EQ(checked, 16 * 16 * 16);
    // A saturated colour keeps its hue family but loses saturation.
    const osg::Vec3f q = ColorQuantization::quantize(osg::Vec3f(0.9f, 0.2f, 0.1f), 5, 0.05f);
    EXPECT_GT(q.x(), q.y());
    EXPECT_GT(q.x(), q.z());
    // Alpha passes through.
    EXPECT_EQ(ColorQuantization::quantize(osg::Vec4f(0.5f, 0.5f, 0.5f, 0.25f), 5, 0.05f).w(), 0.25f);
}

// --- object-space edges (osgLoA::ObjectSpaceEdges) ------------------------------------------------

namespace
{
/** A cube of side 10 as most exporters write it: 24 corners (4 per face, own normals), 6 quads. */
osg::ref_ptr<osg::Geometry> cube24()
{
    osg::ref_ptr<osg::Geometry> g = new osg::Geometry;
    osg::ref_ptr<osg::Vec3Array> v = new osg::Vec3Array;
    osg::ref_ptr<osg::Vec3Array> n = new osg::Vec3Array;
    const osg::Vec3 axes[3] = {osg::Vec3(1, 0, 0), osg::Vec3(0, 1, 0), osg::Vec3(0, 0, 1)};
    for (int a = 0; a < 3; ++a)
        for (float side : {-1.0f, 1.0f})
        {
            const osg::Vec3 nn = axes[a] * side, u = axes[(a + 1) % 3], w = axes[(a + 2) % 3];
            // Counter-clockwise seen from outside.
            const osg::Vec3 c = nn * 5.0f;
            const osg::Vec3 uu = side > 0 ? u : w, ww = side > 0 ? w : u;
            for (const osg::Vec2& q :
                 {osg::Vec2(-1, -1), osg::Vec2(1, -1), osg::Vec2(1, 1), osg::Vec2(-1, 1)})
            {
                v->push_back(c + uu * (5.0f * q.x()) + ww * (5.0f * q.y()));
                n->push_back(nn);
            }
        }
    g->setVertexArray(v.get());
    g->setNormalArray(n.get(), osg::Array::BIND_PER_VERTEX);
    g->addPrimitiveSet(new osg::DrawArrays(GL_QUADS, 0, 24));
    return g;
}
} // namespace

TEST(ObjectSpaceEdgesTest, OctahedralNormalsRoundTrip)
{
    double worst = 0.0;
    for (int i = 0; i < 2000; ++i)
    {
        osg::Vec3f d(std::sin(i * 1.3f) * std::cos(i * 0.7f), std::sin(i * 0.37f), std::cos(i * 2.1f) - 0.3f);
        if (d.normalize() == 0.0f) continue;
        worst = std::max(worst,
                         double((ObjectSpaceEdges::octDecode(ObjectSpaceEdges::octEncode(d)) - d).length()));
    }
    EXPECT_LT(worst, 1e-5);
}

TEST(ObjectSpaceEdgesTest, CubeEdgesAndNeighboursByHand)
{
    // 6 quads = 12 triangles; welded corners make 8 points, 12 cube edges and 6 face diagonals;
    // every edge has two faces. Of the 36 triangle sides, the 24 on cube edges see a neighbour at
    // 90 degrees, the 12 on diagonals one in their own plane.
    osg::ref_ptr<osg::Geometry> g = cube24();
    ObjectSpaceEdges::Report r;
    ASSERT_TRUE(ObjectSpaceEdges::prepareGeometry(*g, r));
    EXPECT_EQ(r.geometries, 1u);
    EXPECT_EQ(r.triangles, 12u);
    EXPECT_EQ(r.edges, 18u);
    EXPECT_EQ(r.boundary, 0u);
    EXPECT_EQ(r.nonManifold, 0u);
    const osg::Vec3Array& v = *static_cast<const osg::Vec3Array*>(g->getVertexArray());
    const osg::Vec4Array& d0 =
        *static_cast<const osg::Vec4Array*>(g->getTexCoordArray(ObjectSpaceEdges::kUnit));
    const osg::Vec4Array& d1 =
        *static_cast<const osg::Vec4Array*>(g->getTexCoordArray(ObjectSpaceEdges::kUnit + 1));
    const osg::Vec4Array& d2 =
        *static_cast<const osg::Vec4Array*>(g->getTexCoordArray(ObjectSpaceEdges::kUnit + 2));
    ASSERT_EQ(v.size(), 36u);
    int perpendicular = 0, coplanar = 0;
    for (unsigned t = 0; t < 12; ++t)
    {
        const osg::Vec3 face = ((v[3 * t + 1] - v[3 * t]) ^ (v[3 * t + 2] - v[3 * t])) / 1.0f;
        osg::Vec3 fn = face;
        fn.normalize();
        for (unsigned k = 0; k < 3; ++k)
        {
            EXPECT_EQ(d0[3 * t + k][k], 1.0f);
            EXPECT_EQ(d0[3 * t + k].w(), 0.0f); // no boundary
        }
        const osg::Vec2f enc[3] = {osg::Vec2f(d1[3 * t].x(), d1[3 * t].y()),
                                   osg::Vec2f(d1[3 * t].z(), d1[3 * t].w()),
                                   osg::Vec2f(d2[3 * t].x(), d2[3 * t].y())};
        for (const osg::Vec2f& e : enc)
        {
            const float c = ObjectSpaceEdges::octDecode(e) * fn;
            perpendicular += std::fabs(c) < 1e-4f;
            coplanar += c > 1.0f - 1e-4f;
        }
    }
    EXPECT_EQ(perpendicular, 24);
    EXPECT_EQ(coplanar, 12);
    // A second preparation leaves the geometry alone.
    ObjectSpaceEdges::Report again;
    ASSERT_TRUE(ObjectSpaceEdges::prepareGeometry(*g, again));
    EXPECT_EQ(again.geometries, 0u);
    EXPECT_EQ(g->getVertexArray()->getNumElements(), 36u);
}

TEST(ObjectSpaceEdgesTest, AnOpenQuadHasFourBoundaryEdges)
{
    osg::ref_ptr<osg::Geometry> g = new osg::Geometry;
    osg::ref_ptr<osg::Vec3Array> v = new osg::Vec3Array;
    for (const osg::Vec3& p :
         {osg::Vec3(0, 0, 0), osg::Vec3(4, 0, 0), osg::Vec3(4, 3, 0), osg::Vec3(0, 3, 0)})
        v->push_back(p);
    g->setVertexArray(v.get());
    osg::ref_ptr<osg::DrawElementsUShort> e = new osg::DrawElementsUShort(GL_TRIANGLES);
    for (unsigned short i : {0, 1, 2, 0, 2, 3})
        e->push_back(i);
    g->addPrimitiveSet(e.get());
    ObjectSpaceEdges::Report r;
    ASSERT_TRUE(ObjectSpaceEdges::prepareGeometry(*g, r));
    EXPECT_EQ(r.edges, 5u);
    EXPECT_EQ(r.boundary, 4u);
    // Each triangle: the diagonal (opposite its corner at index 1 of (0,1,2), at 0 of (0,2,3)) has a
    // neighbour; its two other sides are boundaries.
    const osg::Vec4Array& d0 =
        *static_cast<const osg::Vec4Array*>(g->getTexCoordArray(ObjectSpaceEdges::kUnit));
    EXPECT_EQ(int(d0[0].w()), 1 | 4);
    EXPECT_EQ(int(d0[3].w()), 1 | 2);
    // The style: cartographic with the geometry stage.
    osg::ref_ptr<GraphicStyle> s = GraphicStyleCatalog::instance().create("object-edges");
    ASSERT_TRUE(s.valid());
    EXPECT_EQ(s->getGeometryShader(), "loa_object_edges.geom.glsl");
    EXPECT_NE(s->getParameter("loa_objectEdges_width"), nullptr);
}
