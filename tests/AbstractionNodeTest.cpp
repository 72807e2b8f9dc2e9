// AbstractionNode and AbstractionStyleCatalog without GL: the serializer round trip of a node with
// its style and children, a refused style failing the read, the catalog's names in the graphic
// style catalog, and its refusals.
#include <osgLoA/abstraction/AbstractionNode>
#include <osgLoA/abstraction/AbstractionStyleCatalog>
#include <osgLoA/styles/GraphicStyleCatalog>

#include "support/TestSupport.h"

#include <gtest/gtest.h>

#include <osgDB/ReadFile>
#include <osgDB/WriteFile>

#include <algorithm>
#include <fstream>

using namespace osgLoA;

TEST(AbstractionNodeTest, SerializerRoundTripKeepsStyleAndChildren)
{
    osg::ref_ptr<AbstractionNode> node = new AbstractionNode;
    osg::ref_ptr<AbstractionStyle> style = AbstractionStyle::createBuiltin("adaptive-hybrid-toon");
    style->setCelLevels(5);
    style->getFocus()->setObjectId(42);
    node->setStyle(style.get());
    node->setEnabled(false);
    node->addChild(loatest::boxGeode(osg::Vec3(0, 0, 0), osg::Vec3(1, 2, 3)).get());
    const std::string dir = loatest::freshDirectory("AbstractionNodeTest");
    for (const char* ext : {"osgt", "osgb"})
    {
        const std::string a = dir + "/a." + ext, b = dir + "/b." + ext;
        ASSERT_TRUE(osgDB::writeNodeFile(*node, a));
        osg::ref_ptr<AbstractionNode> back = dynamic_cast<AbstractionNode*>(osgDB::readRefNodeFile(a).get());
        ASSERT_TRUE(back.valid()) << ext;
        ASSERT_TRUE(back->getStyle());
        EXPECT_EQ(back->getStyle()->getName(), "adaptive-hybrid-toon");
        EXPECT_EQ(back->getStyle()->getCelLevels(), 5);
        EXPECT_EQ(back->getStyle()->getFocus()->getObjectId(), 42u);
        EXPECT_FALSE(back->getEnabled());
        EXPECT_EQ(back->getNumChildren(), 1u);
        ASSERT_TRUE(osgDB::writeNodeFile(*back, b));
        EXPECT_EQ(loatest::fileBytes(a), loatest::fileBytes(b)) << ext;
    }
}

TEST(AbstractionNodeTest, ARefusedStyleFailsTheRead)
{
    osg::ref_ptr<AbstractionNode> node = new AbstractionNode;
    node->setStyle(AbstractionStyle::createBuiltin("kuwahara3").get());
    const std::string dir = loatest::freshDirectory("AbstractionNodeRefused");
    ASSERT_TRUE(osgDB::writeNodeFile(*node, dir + "/good.osgt"));
    std::string text = loatest::fileBytes(dir + "/good.osgt");
    const std::size_t at = text.find("KuwaharaRadius 2");
    ASSERT_NE(at, std::string::npos) << text;
    text.replace(at, 16, "KuwaharaRadius 40"); // outside [1, 16]
    {
        std::ofstream out(dir + "/bad.osgt");
        out << text;
    }
    EXPECT_FALSE(osgDB::readRefNodeFile(dir + "/bad.osgt").valid());
    EXPECT_THROW(node->setStyle([] {
        osg::ref_ptr<AbstractionStyle> s = AbstractionStyle::createBuiltin("kuwahara3");
        s->setKuwaharaIterations(9);
        return s;
    }().get()),
                 std::invalid_argument);
}

TEST(AbstractionNodeTest, CatalogStylesAreGraphicStyles)
{
    const std::vector<std::string> graphic = GraphicStyleCatalog::instance().names();
    const std::vector<std::string> abstraction = AbstractionStyleCatalog::instance().names();
    EXPECT_EQ(abstraction, AbstractionStyle::builtinNames());
    for (const std::string& name : abstraction)
        EXPECT_NE(std::find(graphic.begin(), graphic.end(), name), graphic.end()) << name;
    // The graphic styles of before are still there, first.
    EXPECT_EQ(graphic.front(), "photorealistic");

    osg::ref_ptr<AbstractionStyle> mine = AbstractionStyle::createBuiltin("hybrid-pencil");
    mine->setName("my-pencil");
    mine->setPencilGamma(3.0f);
    AbstractionStyleCatalog::instance().add(*mine);
    mine->setPencilGamma(1.0f); // the catalog keeps its own copy
    EXPECT_FLOAT_EQ(AbstractionStyleCatalog::instance().create("my-pencil")->getPencilGamma(), 3.0f);
    EXPECT_TRUE(GraphicStyleCatalog::instance().contains("my-pencil"));

    mine->setName("photorealistic");
    EXPECT_THROW(AbstractionStyleCatalog::instance().add(*mine), std::invalid_argument);
    mine->setName("has space");
    EXPECT_THROW(AbstractionStyleCatalog::instance().add(*mine), std::invalid_argument);
    try
    {
        AbstractionStyleCatalog::instance().create("nope");
        FAIL();
    }
    catch (const std::invalid_argument& e)
    {
        EXPECT_NE(std::string(e.what()).find("hybrid-toon"), std::string::npos) << e.what();
    }
}
