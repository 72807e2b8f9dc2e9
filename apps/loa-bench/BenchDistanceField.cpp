// loa-bench case "distance-field": the region-interest distance map (osgLoA::DistanceField) of a
// scenario-like seed set at 512^2, 1024^2 and 2048^2 texels: CPU seed rasterization, the CPU exact
// EDT (the reference), and the GPU passes of JFA, 1+JFA and JFA+2, with their error against the
// exact EDT; then the three variants on 5000 random points at 1024^2, where they differ.
#include "BenchCase.h"

#include <osgLoA/interest/DistanceField>
#include <osgLoA/render/OffscreenRenderer>

#include <osg/NodeCallback>

#include <chrono>
#include <ctime>
#include <iomanip>
#include <iostream>
#include <random>
#include <sstream>

namespace
{
using DF = osgLoA::DistanceField;

/** 2048 m x 2048 m of ground with what our scenarios put there: a route (a street of 16 m), three
 *  points of interest of 40 m radius and a district polygon. */
DF::RegionList benchRegions()
{
    using R = osgLoA::RegionOfInterest;
    return {
        new R(R::POLYLINE,
              {osg::Vec2d(100, 200), osg::Vec2d(400, 350), osg::Vec2d(700, 300), osg::Vec2d(1000, 650),
               osg::Vec2d(1250, 700), osg::Vec2d(1500, 1100), osg::Vec2d(1800, 1300), osg::Vec2d(1950, 1900)},
              8.0),
        new R(R::CIRCLES, {osg::Vec2d(300, 1500), osg::Vec2d(1600, 400), osg::Vec2d(1100, 1000)}, 40.0),
        new R(R::POLYGON, {osg::Vec2d(500, 1200), osg::Vec2d(900, 1150), osg::Vec2d(1000, 1500),
                           osg::Vec2d(800, 1800), osg::Vec2d(450, 1650)})};
}

/** Makes the passes run in every frame: requestRecompute() (passes only) or setSeeds() (the
 *  seeds packed and uploaded again, then the passes). */
class RecomputeEveryFrame : public osg::NodeCallback
{
public:
    RecomputeEveryFrame(const DF::Seeds* reupload) : _reupload(reupload) {}
    void operator()(osg::Node* node, osg::NodeVisitor* nv) override
    {
        auto* field = static_cast<DF*>(node);
        if (_reupload)
            field->setSeeds(*_reupload);
        else
            field->requestRecompute();
        traverse(node, nv);
    }

private:
    const DF::Seeds* _reupload;
};

/** CPU time of the whole process (all llvmpipe threads), ms: robust to other processes on the
 *  machine, unlike wall time; on an idle machine wall time is at least cpu / cores. */
double processCpuMs()
{
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) * 1e3 + double(t.tv_nsec) / 1e6;
}

std::string cpuNote(double ms)
{
    std::ostringstream o;
    o << std::fixed << std::setprecision(1) << ", cpu " << ms << " ms";
    return o.str();
}

double msSince(std::chrono::steady_clock::time_point t0)
{
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

/** One untimed warm-up, then `frames` timed runs of f. */
template <typename F> osgLoA::FrameTimes timeCpu(unsigned frames, F f, double& cpuMs)
{
    f();
    osgLoA::FrameTimes t;
    const double c0 = processCpuMs();
    for (unsigned i = 0; i < frames; ++i)
    {
        const auto t0 = std::chrono::steady_clock::now();
        f();
        t.milliseconds.push_back(msSince(t0));
    }
    cpuMs = (processCpuMs() - c0) / frames;
    return t;
}

std::string number(double v)
{
    std::ostringstream o;
    o << std::setprecision(4) << v;
    return o.str();
}

void report(const Row& row)
{
    std::cerr << "  " << row.parameters << ": median " << row.times.median() << " ms"
              << (row.errorMean.empty()
                      ? std::string()
                      : ", mean error " + row.errorMean + " texel, > 1 texel " + row.errorMax)
              << "\n";
}
/** The rows of one grid and seed set: "<size> <set> <method> ...", the first three words naming
 *  the row (scripts/charts labels by them), then details. */
void measure(const DF::Grid& grid, const std::string& set, const DF::RegionList& regions, unsigned frames,
             std::string& renderer, std::vector<Row>& rows, bool all)
{
    const std::string name = std::to_string(grid.width) + "x" + std::to_string(grid.height) + " " + set + " ";

    DF::Seeds seeds;
    double cpu = 0.0;
    if (all)
    {
        Row seedRow;
        seedRow.times = timeCpu(
            frames, [&] { seeds = DF::rasterize(grid, regions); }, cpu);
        seedRow.parameters = name + "seeds CPU rasterization, " + std::to_string(seeds.count()) +
                             " seed texels" + cpuNote(cpu);
        rows.push_back(seedRow);
        report(seedRow);
    }
    else
        seeds = DF::rasterize(grid, regions);

    DF::Map exact;
    Row exactRow;
    exactRow.times = timeCpu(
        frames, [&] { exact = DF::computeExact(seeds); }, cpu);
    exactRow.parameters = name + "EDT CPU exact (the reference)" + cpuNote(cpu);
    exactRow.errorMean = "0";
    exactRow.errorMax = "0";
    if (all)
    {
        rows.push_back(exactRow);
        report(exactRow);
    }

    // One renderer per setup (OffscreenRenderer wants its scene data set once).
    osgLoA::OffscreenRenderer::Settings settings;
    settings.width = 1; // the master camera draws nothing; the passes are pre-render cameras
    settings.height = 1;
    osg::ref_ptr<osgLoA::OffscreenRenderer> r = new osgLoA::OffscreenRenderer(settings);
    renderer = r->getCapabilities().renderer;
    DF::checkCapabilities(r->getCapabilities(), grid.width, grid.height);
    osg::ref_ptr<DF> field = new DF;
    field->setGrid(grid);
    field->setUnits(DF::TEXELS);
    field->setSeeds(seeds);
    r->setSceneData(field.get());
    struct Config
    {
        DF::Variant variant;
        bool reupload;
    };
    std::vector<Config> configs = {{DF::JFA, false}, {DF::ONE_PLUS_JFA, false}, {DF::JFA_PLUS_2, false}};
    if (all) configs.push_back({DF::ONE_PLUS_JFA, true});
    for (const Config& c : configs)
    {
        field->setVariant(c.variant);
        field->setUpdateCallback(new RecomputeEveryFrame(c.reupload ? &seeds : nullptr));
        Row row;
        r->timeFrames(0); // the first frame of a setup: FBOs, shader JIT
        const double c0 = processCpuMs();
        row.times = r->timeFrames(frames); // its warm-up frame is an ordinary computation
        cpu = (processCpuMs() - c0) / (frames + 1);
        field->setUpdateCallback(nullptr);
        field->setReadBack(true);
        field->requestRecompute();
        r->renderImage();
        field->setReadBack(false);
        const DF::Error e = DF::compare(field->getReadBackMap(), exact);
        row.parameters = name + DF::toString(c.variant) + (c.reupload ? "+upload" : "") + " GPU " +
                         std::to_string(field->getNumPasses()) + " passes" +
                         (c.reupload ? ", seeds packed and uploaded each time" : "") + cpuNote(cpu);
        row.errorMean = number(e.meanAbs);
        row.errorMax = number(e.fractionOverOne());
        rows.push_back(row);
        report(row);
    }
}
} // namespace

std::vector<Row> distanceField(unsigned frames, std::string& renderer)
{
    std::vector<Row> rows;
    const osg::BoundingBoxd ground(0, 0, 0, 2048, 2048, 0);
    for (int n : {512, 1024, 2048})
        measure(DF::Grid::cover(ground, 2048.0 / n), "scene", benchRegions(), frames, renderer, rows, true);
    // Scattered seeds, where the variants differ: 5000 random points (fixed) at 1024^2.
    DF::RegionList points;
    std::mt19937 rng(2012);
    osg::ref_ptr<osgLoA::RegionOfInterest> circles = new osgLoA::RegionOfInterest;
    for (int i = 0; i < 5000; ++i)
        circles->addVertex(osg::Vec2d(double(rng() % 2048u) + 0.5, double(rng() % 2048u) + 0.5));
    points.push_back(circles);
    measure(DF::Grid::cover(ground, 2.0), "points", points, frames, renderer, rows, false);
    return rows;
}
