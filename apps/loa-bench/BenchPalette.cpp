// loa-bench case "palette" (paper 003): the colour-palette LoA's offline stages, measured on real
// photographs (the skimage images scripts/fetch-test-data extracts from Debian's python3-skimage):
//  - clustering time against table size: the distinct colours of the photographs, each weighted
//    by its texel count (the histogram of a texture mapped once, P_o x P_t uniform), sampled down
//    to n = 1,000 .. 40,000 colours deterministically; Ward (nearest-neighbour chain, O(n^2)
//    time, O(n) memory) and centroid (exact greedy, worst case O(n^3)) linkage;
//  - quantization error against the number of colours: the weighted mean CIELab Delta E of the
//    table to its palette at k = 2 .. 64 colours, hierarchical (Ward, centroid) against weighted
//    k-means (the comparison the paper mentions), on the coffee photograph's table.
//  - rendering cost of the palette style as a ratio to plain rendering (the paper: 200 fps against
//    300 fps for plain OpenGL): the demo city with a palette per texture (PaletteMapping::attach,
//    Ward, 256 levels) drawn by the loa_palette program at a static level of 4, 8, 32 and 256
//    colours, against the loa_plain program, 1280x720 from the oblique camera, glFinish-ended
//    frames after a warm-up; error_max of these rows is the time ratio to plain.
// Times: wall clock of one build per configuration (frames = repetitions of the smaller ones).
// error_mean: the weighted mean Delta E; error_max: for clustering rows, the number of colours.
#include "BenchCase.h"

#include <osgLoA/palette/KMeansPalette>
#include <osgLoA/palette/PaletteHierarchy>
#include <osgLoA/palette/PaletteMapping>
#include <osgLoA/palette/TextureHistogram>
#include <osgLoA/styles/FixedFunctionUniforms>

#include <osgDB/FileUtils>
#include <osgDB/ReadFile>

#include <algorithm>
#include <chrono>
#include <functional>
#include <iomanip>
#include <iostream>
#include <map>
#include <random>
#include <sstream>

namespace
{
using osgLoA::WeightedColor;

/** The distinct colours of an image with their texel counts (uniform texel weights). */
std::vector<WeightedColor> colourTable(const std::string& name)
{
    for (const std::string dir : {"data/cache/python3-skimage/", "../shared/data/images/"})
    {
        if (!osgDB::fileExists(dir + name)) continue;
        osg::ref_ptr<osg::Image> img = osgDB::readRefImageFile(dir + name);
        if (!img) continue;
        const std::vector<double> weights(std::size_t(img->s()) * std::size_t(img->t()), 1.0);
        std::vector<WeightedColor> table;
        for (const auto& e : osgLoA::TextureHistogram::colorTable(*img, weights))
            table.push_back(WeightedColor(osg::Vec3f(e.r, e.g, e.b) / 255.0f, e.weight));
        return table;
    }
    throw std::runtime_error("palette: photograph '" + name +
                             "' not found (run scripts/fetch-test-data to extract the skimage images)");
}

double seconds(const std::function<void()>& fn)
{
    const auto t0 = std::chrono::steady_clock::now();
    fn();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::string number(double v, int precision = 4)
{
    std::ostringstream s;
    s << std::setprecision(precision) << v;
    return s.str();
}
} // namespace

std::vector<Row> palette(unsigned frames, std::string& renderer)
{
    renderer.clear(); // CPU only
    std::vector<Row> rows;
    // All photographs' colours pooled: a table of tens of thousands of colours.
    std::vector<WeightedColor> pool;
    for (const char* photo : {"astronaut.png", "coffee.png", "chelsea.png"})
    {
        const std::vector<WeightedColor> t = colourTable(photo);
        pool.insert(pool.end(), t.begin(), t.end());
    }
    std::mt19937_64 rng(7);
    std::shuffle(pool.begin(), pool.end(), rng);
    std::cerr << "  pooled table: " << pool.size() << " colours\n";
    for (unsigned n : {1000u, 2000u, 5000u, 10000u, 20000u, 40000u, 80000u})
    {
        if (n > pool.size()) break;
        const std::vector<WeightedColor> table(pool.begin(), pool.begin() + n);
        for (auto linkage : {osgLoA::PaletteHierarchy::WARD, osgLoA::PaletteHierarchy::CENTROID})
        {
            if (linkage == osgLoA::PaletteHierarchy::CENTROID && n > 20000) continue; // worst case O(n^3)
            Row row;
            const unsigned reps = n <= 5000 ? std::max(1u, std::min(frames, 5u)) : 1u;
            osg::ref_ptr<osgLoA::PaletteHierarchy> h;
            for (unsigned r = 0; r < reps; ++r)
                row.times.milliseconds.push_back(
                    1000.0 * seconds([&] { h = osgLoA::PaletteHierarchy::build(table, linkage); }));
            row.parameters = std::string("cluster linkage=") + osgLoA::PaletteHierarchy::toString(linkage) +
                             " colors=" + std::to_string(n);
            row.errorMean = number(h->error(32));
            row.errorMax = std::to_string(n);
            rows.push_back(row);
            std::cerr << "  " << row.parameters << ": " << row.times.median() << " ms\n";
        }
    }
    // Quantization error against the number of colours, one photograph's table.
    const std::vector<WeightedColor> coffee = colourTable("coffee.png");
    std::map<osgLoA::PaletteHierarchy::Linkage, osg::ref_ptr<osgLoA::PaletteHierarchy>> trees;
    std::map<osgLoA::PaletteHierarchy::Linkage, double> buildMs;
    for (auto linkage : {osgLoA::PaletteHierarchy::WARD, osgLoA::PaletteHierarchy::CENTROID})
        buildMs[linkage] =
            1000.0 * seconds([&] { trees[linkage] = osgLoA::PaletteHierarchy::build(coffee, linkage); });
    for (unsigned k : {2u, 4u, 8u, 16u, 32u, 64u})
    {
        for (auto linkage : {osgLoA::PaletteHierarchy::WARD, osgLoA::PaletteHierarchy::CENTROID})
        {
            Row row;
            row.parameters = std::string("quantize method=hierarchical-") +
                             osgLoA::PaletteHierarchy::toString(linkage) + " colors=" + std::to_string(k) +
                             " table=" + std::to_string(coffee.size()) + " photo=coffee";
            // The tree is built once for every level: its time is the build's.
            row.times.milliseconds.push_back(buildMs[linkage]);
            row.errorMean = number(trees[linkage]->error(k));
            row.errorMax = std::to_string(k);
            rows.push_back(row);
        }
        Row row;
        row.parameters = "quantize method=kmeans colors=" + std::to_string(k) +
                         " table=" + std::to_string(coffee.size()) + " photo=coffee";
        double err = 0.0;
        row.times.milliseconds.push_back(1000.0 *
                                         seconds([&] { err = osgLoA::KMeansPalette::error(coffee, k); }));
        row.errorMean = number(err);
        row.errorMax = std::to_string(k);
        rows.push_back(row);
        std::cerr << "  k=" << k << ": ward " << trees[osgLoA::PaletteHierarchy::WARD]->error(k)
                  << ", centroid " << trees[osgLoA::PaletteHierarchy::CENTROID]->error(k) << ", k-means "
                  << err << "\n";
    }
    // Rendering cost: the palette program against the plain program on the same city.
    {
        osg::ref_ptr<osg::Group> plain = withPlainProgram(demoCity().get());
        osg::ref_ptr<osg::Node> city = osg::clone(demoCity().get(), osg::CopyOp::DEEP_COPY_STATESETS);
        const double attachMs = 1000.0 * seconds([&] { osgLoA::PaletteMapping::attach(*city); });
        osg::ref_ptr<osg::Group> styled = new osg::Group;
        styled->addChild(city.get());
        osg::StateSet* ss = styled->getOrCreateStateSet();
        ss->setAttributeAndModes(osgLoA::PaletteMapping::createProgram().get());
        ss->addUniform(new osg::Uniform("loa_baseTexture", 0));
        osg::ref_ptr<osg::Uniform> level = new osg::Uniform("loa_palette_level", 8);
        ss->addUniform(level.get());
        ss->addUniform(new osg::Uniform("loa_palette_strategy", 0));
        // Which drawables have a texture (the frame check found the untextured trees black).
        osgLoA::FixedFunctionUniforms::annotate(*city);
        osgLoA::FixedFunctionUniforms::setDefaults(*ss);
        const unsigned n = std::max(3u, frames);
        auto r = makeRenderer(1280, 720, 0, plain.get(), "oblique");
        renderer = r->getCapabilities().renderer;
        Row base;
        base.times = r->timeFrames(n);
        osg::ref_ptr<osg::Image> plainFrame = r->renderImage();
        const std::string plainProblem = checkBlocks(*plainFrame, *plainFrame);
        base.frameFailed = !plainProblem.empty();
        base.parameters = "render style=plain 1280x720 frame=" +
                          (plainProblem.empty() ? std::string("ok") : "FAILED(" + plainProblem + ")");
        base.errorMax = "1";
        rows.push_back(base);
        std::cerr << "  " << base.parameters << ": " << base.times.median() << " ms (palettes attached in "
                  << attachMs << " ms)\n";
        for (int k : {4, 8, 32, 256})
        {
            level->set(k);
            auto rs = makeRenderer(1280, 720, 0, styled.get(), "oblique");
            Row row;
            row.times = rs->timeFrames(n);
            // The timed frame, checked against the plain program's and kept to look at.
            osg::ref_ptr<osg::Image> frame = rs->renderImage();
            const std::string problem = checkFrame(*frame, *plainFrame, rs->getCamera()->getClearColor());
            row.frameFailed = !problem.empty();
            keepFrame(*frame, "palette-1280x720-level" + std::to_string(k));
            row.parameters = "render style=palette 1280x720 level=" + std::to_string(k) +
                             " attach_ms=" + number(attachMs, 5) +
                             " frame=" + (problem.empty() ? std::string("ok") : "FAILED(" + problem + ")");
            row.errorMax = number(row.times.median() / base.times.median());
            rows.push_back(row);
            std::cerr << "  " << row.parameters << ": " << row.times.median() << " ms\n";
        }
    }
    return rows;
}
