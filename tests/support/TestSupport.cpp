#include "TestSupport.h"

#include <stdexcept>

#include <osgLoA/util/ImageCompare>
#include <osgLoA/util/ImageFile>

#include <osg/Geode>
#include <osg/Geometry>
#include <osg/Texture2D>

#include <osgDB/FileUtils>
#include <osgDB/ReadFile>
#include <osgDB/Registry>
#include <osgDB/WriteFile>

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <sys/wait.h>

namespace loatest
{

std::string freshDirectory(const std::string& name)
{
    const std::string dir = std::string(LOA_TEST_OUTPUT_DIR) + "/" + name;
    std::string out;
    run("rm -rf '" + dir + "' && mkdir -p '" + dir + "'", out);
    return dir;
}

void setFilePath(const std::string& value)
{
    ::setenv("OSG_FILE_PATH", value.c_str(), 1);
    osgDB::Registry::instance()->getDataFilePathList().clear();
    osgDB::Registry::instance()->initDataFilePathList();
}

std::string stockToolEnvironment()
{
#ifdef LOA_SANITIZER_PRELOAD
    return "LD_PRELOAD='" LOA_SANITIZER_PRELOAD "' ASAN_OPTIONS=detect_leaks=0 ";
#else
    return std::string();
#endif
}

int run(const std::string& command, std::string& output)
{
    output.clear();
    FILE* p = popen((command + " 2>&1").c_str(), "r");
    if (!p) return -1;
    std::array<char, 4096> buf{};
    size_t n = 0;
    while ((n = fread(buf.data(), 1, buf.size(), p)) > 0)
        output.append(buf.data(), n);
    const int status = pclose(p);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string toOsgt(const osg::Node& node)
{
    // Through a real .osgt file: the text format exactly as users get it.
    static int counter = 0;
    const std::string dir = std::string(LOA_TEST_OUTPUT_DIR);
    osgDB::makeDirectory(dir);
    const std::string path =
        dir + "/toOsgt-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + ".osgt";
    osg::ref_ptr<osgDB::Options> opts = new osgDB::Options("WriteImageHint=IncludeData");
    if (!osgDB::writeNodeFile(node, path, opts.get())) return std::string();
    std::ifstream in(path);
    std::ostringstream text;
    text << in.rdbuf();
    std::remove(path.c_str());
    return text.str();
}

osg::ref_ptr<osg::Image> goldenOrUpdate(const std::string& name, const osg::Image& actual)
{
    const std::string path = std::string(LOA_SOURCE_DIR) + "/tests/data/golden/" + name;
    const char* update = std::getenv("LOA_UPDATE_GOLDENS");
    if (update && std::string(update) == "1")
    {
        osgLoA::ImageFile::write(path, actual);
        return nullptr;
    }
    return osgLoA::ImageFile::read(path);
}

osg::ref_ptr<osg::Geometry> depthQuad(float x0, float x1, float halfHeight, float distance,
                                      const osg::Vec4& color)
{
    osg::ref_ptr<osg::Geometry> g = new osg::Geometry;
    osg::ref_ptr<osg::Vec3Array> v = new osg::Vec3Array;
    v->push_back(osg::Vec3(x0, -halfHeight, -distance));
    v->push_back(osg::Vec3(x1, -halfHeight, -distance));
    v->push_back(osg::Vec3(x1, halfHeight, -distance));
    v->push_back(osg::Vec3(x0, halfHeight, -distance));
    g->setVertexArray(v.get());
    osg::ref_ptr<osg::Vec4Array> c = new osg::Vec4Array;
    c->push_back(color);
    g->setColorArray(c.get(), osg::Array::BIND_OVERALL);
    osg::ref_ptr<osg::Vec3Array> n = new osg::Vec3Array;
    n->push_back(osg::Vec3(0, 0, 1));
    g->setNormalArray(n.get(), osg::Array::BIND_OVERALL);
    g->addPrimitiveSet(new osg::DrawArrays(GL_TRIANGLE_FAN, 0, 4));
    return g;
}

std::string paramName(const std::string& param)
{
    std::string n = param;
    for (char& c : n)
        if (c == '-') c = '_';
    return n;
}

bool matchesAbstractionGolden(const std::string& name, const osg::Image& actual, std::string& summary,
                              bool& skipped)
{
    osg::ref_ptr<osg::Image> golden = goldenOrUpdate(name + ".png", actual);
    skipped = !golden;
    if (skipped) return false;
    const auto cmp = osgLoA::ImageComparison::compare(actual, *golden, 16);
    const bool ok = cmp.sizesMatch && cmp.meanDifference <= 1.0 && cmp.failingFraction <= 0.01;
    if (!ok) saveFailure(name, actual, cmp.difference.get());
    summary = cmp.summary();
    return ok;
}

void saveFailure(const std::string& name, const osg::Image& actual, const osg::Image* difference)
{
    const std::string dir = std::string(LOA_TEST_OUTPUT_DIR) + "/failures";
    osgDB::makeDirectory(dir);
    osgLoA::ImageFile::write(dir + "/" + name + "-actual.png", actual);
    if (difference) osgLoA::ImageFile::write(dir + "/" + name + "-diff.png", *difference);
    std::fprintf(stderr, "saved %s/%s-actual.png and -diff.png\n", dir.c_str(), name.c_str());
}

GpuFilterFixture::GpuFilterFixture() : context(new osgLoA::HeadlessContext)
{
    if (!context->realize() || !context->makeCurrent()) throw std::runtime_error("no EGL context");
    engine = new osgLoA::GpuFilterEngine(*context->getState());
}

GpuFilterFixture::~GpuFilterFixture()
{
    engine->releaseGLObjects();
    context->releaseContext();
}

} // namespace loatest

namespace loatest
{

std::string fileBytes(const std::string& path)
{
    std::ifstream f(path, std::ios::binary);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
}

osg::ref_ptr<osg::Geometry> triangle(const std::string& name)
{
    osg::ref_ptr<osg::Geometry> g = new osg::Geometry;
    g->setName(name);
    osg::ref_ptr<osg::Vec3Array> v = new osg::Vec3Array;
    v->push_back({0, 0, 0});
    v->push_back({1, 0, 0});
    v->push_back({0, 1, 0});
    g->setVertexArray(v.get());
    g->addPrimitiveSet(new osg::DrawArrays(GL_TRIANGLES, 0, 3));
    return g;
}

std::string writeTexturedTriangle(const std::string& path)
{
    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    osg::ref_ptr<osg::Geometry> g = triangle("tri");
    osg::ref_ptr<osg::Image> image = new osg::Image;
    image->allocateImage(4, 4, 1, GL_RGBA, GL_UNSIGNED_BYTE);
    std::memset(image->data(), 200, 64);
    image->setFileName("tex.png");
    g->getOrCreateStateSet()->setTextureAttributeAndModes(0, new osg::Texture2D(image.get()));
    geode->addDrawable(g.get());
    osg::ref_ptr<osgDB::Options> o = new osgDB::Options("WriteImageHint=IncludeData");
    EXPECT_TRUE(osgDB::writeNodeFile(*geode, path, o.get())) << path;
    return fileBytes(path);
}

osgLoA::FilterImage photoCrop(const std::string& name, int x0, int y0, int w, int h)
{
    for (const std::string& dir : {std::string(LOA_SOURCE_DIR "/data/cache/python3-skimage/"),
                                   std::string(LOA_SOURCE_DIR "/../shared/data/images/")})
    {
        if (!osgDB::fileExists(dir + name)) continue;
        osg::ref_ptr<osg::Image> image = osgDB::readRefImageFile(dir + name);
        if (!image) continue;
        const osgLoA::FilterImage full = osgLoA::FilterImage::fromImage(*image);
        osgLoA::FilterImage out(w, h);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                out.set(x, y, full.get(x0 + x, y0 + y));
        return out;
    }
    return osgLoA::FilterImage();
}

std::string replaced(std::string text, const std::string& from, const std::string& to)
{
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return text;
}

} // namespace loatest
