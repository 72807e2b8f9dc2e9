// loa-bench case "interest": ScenarioEvaluator::evaluate per frame (CPU, one thread) for 1k, 10k
// and 100k features and the built-in distance, route and view-angle scenarios, plus the cost of
// the fragment-mode conservative flags (matches flagged mayContribute that draw nothing).
#include "BenchCase.h"

#include <osgLoA/semantics/Feature>
#include <osgLoA/semantics/FeatureIndex>
#include <osgLoA/transitions/ScenarioEvaluator>
#include <osgLoA/transitions/ScenarioLibrary>

#include <osg/Group>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <random>
#include <sstream>

namespace
{
using namespace osgLoA;

/** A synthetic city of n features on a grid of 30 m cells around the origin: mostly buildings
 *  (16x16 m footprints, 5-40 m high), streets along every tenth column (whole 30x8 m cells),
 *  green spaces along every tenth row, some water cells, and a 90x90 m terrain tile every 97th
 *  cell; 2% of the buildings are landmarks (interest 1). Each feature sits on its own node and
 *  its box is set directly (the evaluator reads only the Feature's bound). */
struct SyntheticCity
{
    osg::ref_ptr<osg::Group> root = new osg::Group;
    FeatureIndex index;

    explicit SyntheticCity(unsigned n)
    {
        std::mt19937 rng(n);
        std::uniform_real_distribution<float> height(5.0f, 40.0f), u(0.0f, 1.0f);
        const unsigned side = unsigned(std::ceil(std::sqrt(double(n))));
        const float cell = 30.0f, origin = -0.5f * cell * float(side);
        for (unsigned i = 0; i < n; ++i)
        {
            const unsigned cx = i % side, cy = i / side;
            const float x = origin + cell * float(cx), y = origin + cell * float(cy);
            FeatureType type = FeatureType::Building;
            osg::BoundingBoxf b(x + 7, y + 7, 0, x + 23, y + 23, height(rng));
            if (i % 97 == 0)
            {
                type = FeatureType::Terrain;
                b.set(x - 30, y - 30, -2, x + 60, y + 60, 0);
            }
            else if (cx % 10 == 0)
            {
                type = FeatureType::Street;
                b.set(x, y + 11, 0, x + 30, y + 19, 0.2f);
            }
            else if (cy % 10 == 5)
            {
                type = FeatureType::Green;
                b.set(x, y, 0, x + 30, y + 30, 12);
            }
            else if ((cx * 7 + cy * 3) % 23 == 0)
            {
                type = FeatureType::Water;
                b.set(x, y, -1, x + 30, y + 30, 0);
            }
            osg::ref_ptr<Feature> f = new Feature(i + 1, type);
            f->setBound(b);
            if (type == FeatureType::Building && u(rng) < 0.02f) f->setInterest(1.0f);
            osg::ref_ptr<osg::Node> node = new osg::Node;
            Feature::attach(*node, f.get());
            root->addChild(node.get());
        }
        index.build(*root);
    }
};

double msSince(std::chrono::steady_clock::time_point t0)
{
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

/** Eye for frame i: circling the centre at 600 m radius, 300 m high, looking anywhere (the
 *  evaluator does not look; every feature counts as visible). */
osg::Vec3d eyeAt(unsigned i)
{
    const double a = 0.37 * double(i);
    return osg::Vec3d(600.0 * std::cos(a), 600.0 * std::sin(a), 300.0);
}

/** The cost of conservatism: of the fragment matches flagged mayContribute, the fraction whose
 *  weight is 0 at every point of a dense sampling of the box (17x17 points on its top and on
 *  its bottom face, and the 8 corners). Also counts the opposite error (flag false, some sample
 *  > 0), which must never happen. At most 3000 flagged matches per evaluation are sampled. */
struct Conservatism
{
    unsigned sampled = 0, wasted = 0, missed = 0;
    void measure(const ScenarioEvaluator& e, const UsageScenario& s)
    {
        const auto& configs = s.getConfigurations();
        std::vector<unsigned> flagged, unflagged;
        for (std::size_t i = 0; i < e.matches().size(); ++i)
            if (e.matches()[i].fragment)
                (e.matches()[i].mayContribute ? flagged : unflagged).push_back(unsigned(i));
        std::vector<const ScenarioEvaluator::FeatureState*> owner(e.matches().size(), nullptr);
        for (const ScenarioEvaluator::FeatureState& f : e.features())
            for (unsigned k = 0; k < f.numMatches; ++k)
                owner[f.firstMatch + k] = &f;
        auto anyWeight = [&](unsigned mi)
        {
            const ScenarioEvaluator::Match& m = e.matches()[mi];
            const ScenarioEvaluator::FeatureState& f = *owner[mi];
            const TransitionConfiguration& c = *configs[m.configuration];
            const BlendFunction blend = c.getBlendFunction();
            const osg::BoundingBoxd& b = f.bound;
            const int n = 16;
            for (int k = 0; k < 2; ++k)
                for (int j = 0; j <= n; ++j)
                    for (int i = 0; i <= n; ++i)
                    {
                        const osg::Vec3d p(b.xMin() + (b.xMax() - b.xMin()) * i / n,
                                           b.yMin() + (b.yMax() - b.yMin()) * j / n, k ? b.zMax() : b.zMin());
                        if (blend.weight(float(c.interestAt(p, e.getView(), f.staticInterest))) > 0.0f)
                            return true;
                    }
            return false;
        };
        const std::size_t step = std::max<std::size_t>(1, flagged.size() / 3000);
        for (std::size_t i = 0; i < flagged.size(); i += step)
        {
            ++sampled;
            if (!anyWeight(flagged[i])) ++wasted;
        }
        const std::size_t step2 = std::max<std::size_t>(1, unflagged.size() / 3000);
        for (std::size_t i = 0; i < unflagged.size(); i += step2)
            if (anyWeight(unflagged[i])) ++missed;
    }
};
} // namespace

std::vector<Row> interest(unsigned frames, std::string& renderer)
{
    renderer = "";
    std::vector<Row> rows;
    for (unsigned n : {1000u, 10000u, 100000u})
    {
        const auto tCity = std::chrono::steady_clock::now();
        SyntheticCity city(n);
        std::cerr << "  synthetic city of " << n << " features: " << std::fixed << std::setprecision(0)
                  << msSince(tCity) << " ms\n";
        for (const char* name : {"distance", "route", "view-angle"})
        {
            osg::ref_ptr<UsageScenario> scenario = ScenarioLibrary::createBuiltin(name);
            osg::ref_ptr<ScenarioEvaluator> e = new ScenarioEvaluator;
            const auto tBind = std::chrono::steady_clock::now();
            e->bind(scenario.get(), city.index);
            const double bindMs = msSince(tBind);
            e->evaluate(eyeAt(0)); // warm-up
            Row row;
            Conservatism cons;
            std::vector<double> wastedPerFrame;
            for (unsigned i = 1; i <= frames; ++i)
            {
                const osg::Vec3d eye = eyeAt(i);
                const auto t0 = std::chrono::steady_clock::now();
                e->evaluate(eye);
                row.times.milliseconds.push_back(msSince(t0));
            }
            const ScenarioEvaluator::Statistics st = e->getStatistics();
            // The accuracy measure, after the timing, for the eyes of the first five frames.
            for (unsigned i = 1; i <= 5; ++i)
            {
                e->evaluate(eyeAt(i));
                Conservatism c;
                c.measure(*e, *scenario);
                if (c.sampled) wastedPerFrame.push_back(double(c.wasted) / c.sampled);
                cons.sampled += c.sampled;
                cons.wasted += c.wasted;
                cons.missed += c.missed;
            }
            unsigned fragments = 0;
            for (const ScenarioEvaluator::Match& m : e->matches())
                fragments += m.fragment ? 1u : 0u;
            std::ostringstream p;
            p << std::fixed << std::setprecision(1) << "scenario=" << name << " features=" << n
              << " matches=" << st.matches << " fragment_matches=" << fragments << " bind_ms=" << bindMs
              << " ns_per_feature=" << std::setprecision(0) << row.times.median() * 1e6 / n
              << " sampled=" << cons.sampled << " false_negatives=" << cons.missed;
            row.parameters = p.str();
            if (!wastedPerFrame.empty())
            {
                double mean = 0.0, mx = 0.0;
                for (double w : wastedPerFrame)
                {
                    mean += w;
                    mx = std::max(mx, w);
                }
                std::ostringstream m, x;
                m << std::setprecision(4) << mean / double(wastedPerFrame.size());
                x << std::setprecision(4) << mx;
                row.errorMean = m.str();
                row.errorMax = x.str();
            }
            rows.push_back(row);
            std::cerr << "  " << row.parameters << ": median " << std::setprecision(3) << row.times.median()
                      << " ms, wasted fragment draws " << row.errorMean << " (max " << row.errorMax << ")\n";
        }
    }
    return rows;
}
