// loa-bench --case classify-objects: how the object grouping of the classifier (one real
// object, one feature) trades time for agreement with the hand counts on real scenes.
#include "BenchCase.h"

#include <osgLoA/semantics/FeatureClassifier>
#include <osgLoA/semantics/FeatureIndex>

#include <osgDB/FileUtils>
#include <osgDB/ReadFile>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>

std::vector<Row> classifyObjects(unsigned frames, std::string& renderer)
{
    renderer = "";
    struct Variant
    {
        const char* name;
        bool group;
        const char* mergeTypes;
        float tolerance;
    };
    const Variant variants[] = {{"geodes", false, "", 0.0f},
                                {"transforms", true, "", 0.0f},
                                {"transforms+touching(0.05)", true, "building", 0.05f},
                                {"transforms+touching(0.5)", true, "building", 0.5f}};
    std::vector<Row> rows;
    for (const char* scene : {"torcs-street-1", "opencity-block"})
    {
        const std::string model = "data/test-scenes/" + std::string(scene) + ".osgt";
        const std::string counts = "data/test-scenes/" + std::string(scene) + ".counts.json";
        if (!osgDB::fileExists(counts) || !osgDB::readRefNodeFile(model))
        {
            std::cerr << "  " << scene
                      << ": not found (run from the repository root after scripts/fetch-test-data)\n";
            continue;
        }
        std::ifstream in(counts);
        const nlohmann::json hand = nlohmann::json::parse(in)["counts"];
        for (const Variant& v : variants)
        {
            Row row;
            double errorSum = 0.0, handSum = 0.0, worst = 0.0;
            unsigned features = 0;
            for (unsigned i = 0; i < std::max(frames, 1u); ++i)
            {
                osg::ref_ptr<osg::Node> node = osgDB::readRefNodeFile(model); // classifying changes it
                osg::ref_ptr<osgLoA::ClassificationRuleSet> rules =
                    osgLoA::ClassificationRuleSet::createDefault();
                rules->setGroupObjects(v.group);
                rules->setMergeTouchingTypes(v.mergeTypes);
                rules->setMergeTolerance(v.tolerance);
                const auto t0 = std::chrono::steady_clock::now();
                osgLoA::FeatureClassifier(rules.get()).classify(*node);
                row.times.milliseconds.push_back(
                    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
                const osgLoA::FeatureIndex::Counts c = osgLoA::FeatureIndex(*node).counts();
                features = c.total;
                errorSum = handSum = worst = 0.0;
                for (osgLoA::FeatureType t : osgLoA::kFeatureTypes)
                {
                    const double h = hand[osgLoA::toString(t)]["hand"].get<double>();
                    const double e = std::fabs(double(c.get(t)) - h);
                    errorSum += e;
                    handSum += h;
                    worst = std::max(worst, e / std::max(h, 1.0));
                }
            }
            std::ostringstream p, m, x;
            p << scene << " " << v.name << " features=" << features;
            m << std::setprecision(4) << errorSum / std::max(handSum, 1.0);
            x << std::setprecision(4) << worst;
            row.parameters = p.str();
            row.errorMean = m.str();
            row.errorMax = x.str();
            std::cerr << "  " << row.parameters << ": median " << row.times.median() << " ms, count error "
                      << row.errorMean << " (worst type " << row.errorMax << ")\n";
            rows.push_back(row);
        }
    }
    return rows;
}
