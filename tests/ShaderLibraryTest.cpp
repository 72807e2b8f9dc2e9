// Shader sources: embedding, stage names, and overrides through OSG_FILE_PATH (no GL needed).
#include "support/TestSupport.h"

#include <osgLoA/render/ShaderLibrary>

#include <osgDB/Registry>

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <regex>
#include <unistd.h>

using namespace osgLoA;

TEST(ShaderLibraryTest, EverySourceOfShadersIsEmbeddedWithAVersionLine)
{
    const auto names = ShaderLibrary::embeddedNames();
    ASSERT_FALSE(names.empty());
    EXPECT_NE(std::find(names.begin(), names.end(), "loa_plain.vert.glsl"), names.end());
    EXPECT_NE(std::find(names.begin(), names.end(), "loa_plain.frag.glsl"), names.end());
    loatest::setFilePath("");
    int includes = 0;
    for (const auto& n : names)
    {
        const auto src = ShaderLibrary::getSource(n);
        EXPECT_EQ(src.origin, "embedded");
        if (ShaderLibrary::isInclude(n))
        {
            ++includes; // included text: no #version of its own
            EXPECT_EQ(src.text.find("#version"), std::string::npos) << n;
            continue;
        }
        EXPECT_EQ(src.text.rfind("#version ", 0), 0u) << n;
        EXPECT_FALSE(std::regex_search(src.text, std::regex("(^|\n)[ \t]*#pragma[ \t]+include")))
            << n << ": an include left unresolved";
    }
    EXPECT_GE(includes, 2);
}

TEST(ShaderLibraryTest, IncludesAreInsertedOnceWithLineDirectives)
{
    // The five flow-guided filters share the structure tensor's eigen-analysis by include.
    loatest::setFilePath("");
    for (const char* n :
         {"loa_filter_akf.comp.glsl", "loa_filter_shock.comp.glsl", "loa_filter_tensor.comp.glsl",
          "loa_filter_fdog.comp.glsl", "loa_filter_flowbilateral.comp.glsl"})
    {
        const auto src = ShaderLibrary::getSource(n);
        ASSERT_EQ(src.includes, std::vector<std::string>{"loa_structure_tensor.glsl"}) << n;
        const std::size_t definition = src.text.find("vec4 loa_flowOfTensor(vec3 efg)");
        ASSERT_NE(definition, std::string::npos) << n;
        EXPECT_EQ(src.text.find("vec4 loa_flowOfTensor(vec3 efg)", definition + 1), std::string::npos) << n;
        EXPECT_NE(src.text.find("#line 1 1\n"), std::string::npos) << n;
    }

    // Nested, repeated and overridden includes; line numbers continue after each.
    const std::string dir = loatest::freshDirectory("ShaderInclude");
    auto write = [&](const std::string& name, const std::string& text)
    { std::ofstream(dir + "/" + name) << text; };
    write("top.frag.glsl",
          "#version 450\n#pragma include \"a.glsl\"\nX\n  #pragma  include  \"b.glsl\"\nY\n");
    write("a.glsl", "A1\n#pragma include \"b.glsl\"\nA3\n");
    write("b.glsl", "B1\n");
    loatest::setFilePath(dir);
    const auto src = ShaderLibrary::getSource("top.frag.glsl");
    EXPECT_EQ(src.includes, (std::vector<std::string>{"a.glsl", "b.glsl"}));
    EXPECT_EQ(src.text, "#version 450\n#line 1 1\nA1\n#line 1 2\nB1\n#line 3 1\nA3\n#line 3 0\nX\n"
                        "// (b.glsl is included above)\nY\n");
    EXPECT_TRUE(ShaderLibrary::isInclude("a.glsl"));
    EXPECT_FALSE(ShaderLibrary::isInclude("top.frag.glsl"));

    // A cycle, a missing file and a malformed pragma are errors that name the files.
    write("cycle.frag.glsl", "#version 450\n#pragma include \"c1.glsl\"\n");
    write("c1.glsl", "#pragma include \"c2.glsl\"\n");
    write("c2.glsl", "\n#pragma include \"c1.glsl\"\n");
    write("missing.frag.glsl", "#version 450\n\n#pragma include \"nowhere.glsl\"\n");
    write("bad.frag.glsl", "#version 450\n#pragma include nowhere.glsl\n");
    auto error = [](const std::string& name)
    {
        try
        {
            ShaderLibrary::getSource(name);
        }
        catch (const std::invalid_argument& e)
        {
            return std::string(e.what());
        }
        return std::string("(no error)");
    };
    EXPECT_EQ(error("cycle.frag.glsl"),
              "shader include cycle: cycle.frag.glsl -> c1.glsl -> c2.glsl -> c1.glsl (at 'c2.glsl' line 2)");
    EXPECT_EQ(error("missing.frag.glsl"),
              "shader include 'nowhere.glsl' (at 'missing.frag.glsl' line 3) is not "
              "embedded and not on OSG_FILE_PATH");
    EXPECT_NE(error("bad.frag.glsl").find("malformed include"), std::string::npos);
    loatest::setFilePath("");
}

TEST(ShaderLibraryTest, AFileOnOsgFilePathOverridesTheEmbeddedSource)
{
    const std::string dir = loatest::freshDirectory("ShaderOverride");
    {
        std::ofstream out(dir + "/loa_plain.frag.glsl");
        out << "#version 450 compatibility\n// OVERRIDDEN\nvoid main() { gl_FragColor = vec4(1); }\n";
    }
    loatest::setFilePath("/nonexistent:" + dir);
    const auto src = ShaderLibrary::getSource("loa_plain.frag.glsl");
    EXPECT_EQ(src.origin, dir + "/loa_plain.frag.glsl");
    EXPECT_NE(src.text.find("OVERRIDDEN"), std::string::npos);
    // The other stage is not overridden.
    EXPECT_EQ(ShaderLibrary::getSource("loa_plain.vert.glsl").origin, "embedded");
    // The shader object carries the source and the file it came from.
    auto shader = ShaderLibrary::createShader("loa_plain.frag.glsl");
    EXPECT_NE(shader->getShaderSource().find("OVERRIDDEN"), std::string::npos);
    EXPECT_EQ(shader->getName(), "loa_plain.frag.glsl");
    loatest::setFilePath("");
    EXPECT_EQ(ShaderLibrary::getSource("loa_plain.frag.glsl").origin, "embedded");
}

TEST(ShaderLibraryTest, TheWorkingDirectoryDoesNotOverride)
{
    const std::string dir = loatest::freshDirectory("ShaderCwd");
    {
        std::ofstream out(dir + "/loa_plain.vert.glsl");
        out << "#version 450\n// STRAY\n";
    }
    loatest::setFilePath("");
    char old[4096];
    ASSERT_NE(::getcwd(old, sizeof old), nullptr);
    ASSERT_EQ(::chdir(dir.c_str()), 0);
    const auto src = ShaderLibrary::getSource("loa_plain.vert.glsl");
    ASSERT_EQ(::chdir(old), 0);
    EXPECT_EQ(src.origin, "embedded");
}

TEST(ShaderLibraryTest, StagesComeFromTheName)
{
    EXPECT_EQ(ShaderLibrary::stageOf("a.vert.glsl"), osg::Shader::VERTEX);
    EXPECT_EQ(ShaderLibrary::stageOf("a.frag.glsl"), osg::Shader::FRAGMENT);
    EXPECT_EQ(ShaderLibrary::stageOf("a.comp.glsl"), osg::Shader::COMPUTE);
    EXPECT_EQ(ShaderLibrary::stageOf("a.geom.glsl"), osg::Shader::GEOMETRY);
    EXPECT_THROW(ShaderLibrary::stageOf("a.glsl"), std::invalid_argument);
    EXPECT_THROW(ShaderLibrary::stageOf("a.vert"), std::invalid_argument);
    EXPECT_THROW(ShaderLibrary::getSource("loa_missing.frag.glsl"), std::invalid_argument);
}

TEST(ShaderLibraryTest, DiagnosticsNameShaderStageAndProgram)
{
    ShaderDiagnostic d{"plain", "loa_plain.frag.glsl", "fragment", "0:3(1): error: syntax error\n"};
    EXPECT_EQ(d.message(),
              "shader 'loa_plain.frag.glsl' (fragment stage) of program 'plain' failed to compile: "
              "0:3(1): error: syntax error");
    ShaderDiagnostic l{"plain", "(link)", "link", ""};
    EXPECT_EQ(l.message(), "program 'plain' failed to link: (the driver gave no log)");
}

// Defines go right after the #version line, followed by a #line directive that gives the next
// line the number it has in the file (the driver's messages keep the file's line numbers); the
// shader's name lists them. One program can so link a function defined in two sources under
// two names (TransitionRenderer's fused styles: `#define loa_styleColor loa_styleColor_k`).
TEST(ShaderLibraryTest, DefinesGoAfterTheVersionLineAndKeepLineNumbers)
{
    loatest::setFilePath("");
    const std::string name = "loa_style_cartographic.frag.glsl";
    const std::string original = ShaderLibrary::getSource(name).text;
    const std::size_t firstEol = original.find('\n');
    ASSERT_EQ(original.substr(0, firstEol), "#version 450 compatibility");
    osg::ref_ptr<osg::Shader> shader =
        ShaderLibrary::createShader(name, {{"loa_styleColor", "loa_styleColor_3"}, {"LOA_TEST_FLAG", ""}});
    const std::string expectedHead = "#version 450 compatibility\n#define loa_styleColor loa_styleColor_3\n"
                                     "#define LOA_TEST_FLAG 1\n#line 2 0\n";
    const std::string text = shader->getShaderSource();
    ASSERT_EQ(text.substr(0, expectedHead.size()), expectedHead);
    EXPECT_EQ(text.substr(expectedHead.size()), original.substr(firstEol + 1));
    EXPECT_EQ(shader->getName(), name + "[loa_styleColor=loa_styleColor_3 LOA_TEST_FLAG]");
    EXPECT_EQ(shader->getType(), osg::Shader::FRAGMENT);
    // No defines: the plain shader.
    EXPECT_EQ(ShaderLibrary::createShader(name, {})->getShaderSource(), original);
    // A file whose #version is not its first line (a comment above it): the #line counts it.
    const std::string dir = loatest::freshDirectory("ShaderDefinesVersionLater");
    std::ofstream(dir + "/loa_test_defines.frag.glsl") << "// a comment\n#version 450 core\nvoid f() {}\n";
    loatest::setFilePath(dir);
    const std::string later =
        ShaderLibrary::createShader("loa_test_defines.frag.glsl", {{"A", "2"}})->getShaderSource();
    loatest::setFilePath("");
    EXPECT_EQ(later, "// a comment\n#version 450 core\n#define A 2\n#line 3 0\nvoid f() {}\n");
    // Names that are not identifiers and values that span lines are refused, with the name.
    for (const ShaderLibrary::Defines& bad :
         {ShaderLibrary::Defines{{"2x", ""}}, ShaderLibrary::Defines{{"A B", ""}},
          ShaderLibrary::Defines{{"", "1"}}, ShaderLibrary::Defines{{"A", "1\n#define B 2"}}})
    {
        try
        {
            ShaderLibrary::createShader(name, bad);
            ADD_FAILURE() << "accepted the define '" << bad[0].first << "'";
        }
        catch (const std::invalid_argument& e)
        {
            EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
        }
    }
}

// Shader and program names become GL object labels, which GL refuses at GL_MAX_LABEL_LENGTH
// characters or more (256 on Mesa: "GL_INVALID_VALUE in glObjectLabel(length=351)" for a fused
// style shader named by its renamed helpers). Names stay within 255 characters.
TEST(ShaderLibraryTest, NamesFitAGLObjectLabel)
{
    EXPECT_EQ(ShaderLibrary::objectLabel("loa_plain.vert.glsl"), "loa_plain.vert.glsl");
    const std::string exact(255, 'a');
    EXPECT_EQ(ShaderLibrary::objectLabel(exact), exact);
    const std::string longer = std::string(250, 'b') + "cdefghij";
    const std::string cut = ShaderLibrary::objectLabel(longer);
    EXPECT_EQ(cut.size(), 255u);
    EXPECT_EQ(cut, std::string(250, 'b') + "cd...");

    ShaderLibrary::Defines renames;
    for (int i = 0; i < 30; ++i)
        renames.emplace_back("loa_helperNumber" + std::to_string(i),
                             "loa_helperNumber" + std::to_string(i) + "_3");
    osg::ref_ptr<osg::Shader> s = ShaderLibrary::createShader("loa_style_abstract.frag.glsl", renames);
    EXPECT_LE(s->getName().size(), 255u);
    EXPECT_EQ(s->getName().compare(0, 28, "loa_style_abstract.frag.glsl"), 0) << s->getName();
    EXPECT_NE(s->getShaderSource().find("#define loa_helperNumber29 loa_helperNumber29_3"),
              std::string::npos);
}
