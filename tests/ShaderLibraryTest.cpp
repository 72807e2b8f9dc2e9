// Shader sources: embedding, stage names, and overrides through OSG_FILE_PATH (no GL needed).
#include "support/TestSupport.h"

#include <osgLoA/render/ShaderLibrary>

#include <osgDB/Registry>

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <unistd.h>

using namespace osgLoA;

TEST(ShaderLibraryTest, EverySourceOfShadersIsEmbeddedWithAVersionLine)
{
    const auto names = ShaderLibrary::embeddedNames();
    ASSERT_FALSE(names.empty());
    EXPECT_NE(std::find(names.begin(), names.end(), "loa_plain.vert.glsl"), names.end());
    EXPECT_NE(std::find(names.begin(), names.end(), "loa_plain.frag.glsl"), names.end());
    loatest::setFilePath("");
    for (const auto& n : names)
    {
        const auto src = ShaderLibrary::getSource(n);
        EXPECT_EQ(src.origin, "embedded");
        EXPECT_EQ(src.text.rfind("#version ", 0), 0u) << n;
    }
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
