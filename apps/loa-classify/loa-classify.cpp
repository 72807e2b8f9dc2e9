// loa-classify: loads a model, classifies its features, prints the count per type, and can
// render the debug view coloured by feature type (paper 004, Figure 3B).
#include "../common/AppSupport.h"
#include "../common/CommandLine.h"

#include <osgLoA/Version>
#include <osgLoA/render/OffscreenRenderer>
#include <osgLoA/semantics/ClassificationRuleSet>
#include <osgLoA/semantics/FeatureClassifier>
#include <osgLoA/semantics/FeatureIndex>
#include <osgLoA/semantics/FeatureInterest>
#include <osgLoA/semantics/FeatureTypeView>
#include <osgLoA/semantics/ViewpointEntropy>
#include <osgLoA/util/AtomicFile>
#include <osgLoA/util/ImageFile>

#include <osgDB/FileNameUtils>
#include <osgDB/ReadFile>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <iostream>

namespace
{
const char* kDescription =
    R"(Loads MODEL (any file osgDB reads through the plugins: .cityjson, .city.json, .gml, .osm,
.osm.pbf, .osm.bz2, .osgb, .obj, demo.loacity ...), classifies its features and prints how many
features of each type it holds; several MODELs are one scene, classified together. Features
that the model data already typed keep their type; the rules classify the rest, and the
appearance fallback what no rule matched (docs/classification.md).
)";
const char* kFooter =
    R"(exit status: 0 done, 1 the model, the rules or an output could not be read or written,
2 bad arguments, 3 no usable EGL/OpenGL context (only with --image).
)";

struct Options
{
    std::vector<std::string> models; ///< MODEL arguments (several: one scene)
    std::string model, image, save, writeRules, interest, readerOptions;
    loa::RulesChoice rules;
    bool json = false, bestViews = false;
    float landmarkThreshold = -1.0f;
    int width = loa::kDefaultWidth, height = loa::kDefaultHeight;
    loa::CameraChoice camera;
};

Options parse(int argc, char** argv)
{
    Options o;
    loa::CommandLine cl("loa-classify", "loa-classify MODEL... [options]", kDescription);
    CLI::App& app = cl.app();
    loa::addModels(app, o.models, "the models to classify as one scene");
    loa::addReaderOptions(app, o.readerOptions);
    loa::addRules(app, o.rules);
    loa::addCamera(app, o.camera);
    loa::addSize(app, o.width, o.height, "the --image debug view");
    app.add_option(
           "--image", o.image,
           "render the debug view coloured by feature type: building red, street grey, water blue, green "
           "space green, terrain sand, generic magenta, landmarks gold")
        ->type_name("FILE.png")
        ->group(loa::kGroupOutput);
    app.add_option("--save", o.save, "write the classified model (.osgb, .osgt, ...; written atomically)")
        ->type_name("FILE")
        ->group(loa::kGroupOutput);
    app.add_option("--interest", o.interest,
                   "interest values per type and per feature id and the landmark threshold (an "
                   "osgLoA::FeatureInterest in .osgt/.osgb; docs/landmarks.md)")
        ->type_name("FILE");
    app.add_option_function<std::string>(
           "--landmark-threshold",
           [&o](const std::string& v)
           {
               char* end = nullptr;
               o.landmarkThreshold = std::strtof(v.c_str(), &end);
               if (end == v.c_str() || *end || !(o.landmarkThreshold >= 0.0f && o.landmarkThreshold <= 1.0f))
                   throw loa::UsageError("--landmark-threshold '" + v + "' must be a number in [0,1]");
           },
           "features with interest >= T (in [0,1]) are landmarks (default: the landmarks the model data "
           "flags)")
        ->type_name("T");
    app.add_flag("--best-views", o.bestViews,
                 "compute each landmark's best view by viewpoint entropy (headless GL) and print it");
    app.add_flag("--json", o.json,
                 "print one JSON object: {\"building\": n, \"street\": n, \"water\": n, \"green\": n, "
                 "\"terrain\": n, \"generic\": n, \"landmarks\": n}");
    app.add_option("--write-default-rules", o.writeRules,
                   "write the built-in rule set to FILE (a starting point for your own) and exit")
        ->type_name("FILE");
    cl.footer(kFooter);
    cl.parse(argc, argv);
    o.model = loa::modelLabel(o.models);
    loa::checkCameraOptions(o.camera);
    if (o.writeRules.empty() && o.model.empty()) throw loa::UsageError("no MODEL given (see --help)");
    if (!o.image.empty() && osgDB::getLowerCaseFileExtension(o.image) != "png")
        throw loa::UsageError("--image '" + o.image + "' must name a .png file");
    return o;
}

int run(const Options& o)
{
    if (!o.writeRules.empty())
    {
        osgLoA::ClassificationRuleSet::createDefault()->write(o.writeRules);
        std::cout << "wrote " << o.writeRules << "\n";
        return loa::kOk;
    }
    osg::ref_ptr<osgLoA::ClassificationRuleSet> rules = o.rules.assemble();

    const auto t0 = std::chrono::steady_clock::now();
    osg::ref_ptr<osg::Node> scene = loa::loadModels(o.models, o.readerOptions);
    if (o.models.size() > 1)
    {
        const std::vector<unsigned> duplicates = osgLoA::FeatureIndex(*scene).duplicateIds();
        if (!duplicates.empty())
            std::cerr << "loa-classify: warning: " << duplicates.size()
                      << " feature ids occur in more than one model (first: " << duplicates.front() << ")\n";
    }
    const auto t1 = std::chrono::steady_clock::now();
    const osgLoA::FeatureClassifier::Report report = osgLoA::FeatureClassifier(rules.get()).classify(*scene);
    const auto t2 = std::chrono::steady_clock::now();
    osgLoA::FeatureIndex index(*scene);
    if (!o.interest.empty() || o.landmarkThreshold >= 0.0f)
    {
        osg::ref_ptr<osgLoA::FeatureInterest> fi = new osgLoA::FeatureInterest;
        fi->setKeepExistingInterest(true);
        if (!o.interest.empty())
        {
            osg::ref_ptr<osg::Object> obj = osgDB::readRefObjectFile(o.interest);
            fi = dynamic_cast<osgLoA::FeatureInterest*>(obj.get());
            if (!fi)
                throw std::runtime_error("cannot read interest values from '" + o.interest + "'" +
                                         (obj ? std::string(": it holds a ") + obj->className() +
                                                    ", not an osgLoA::FeatureInterest"
                                              : std::string(": no such file or not readable")));
        }
        if (o.landmarkThreshold >= 0.0f) fi->setLandmarkThreshold(o.landmarkThreshold);
        fi->apply(index);
    }
    std::vector<osgLoA::ViewpointEntropy::Result> views;
    if (o.bestViews)
        osg::ref_ptr<osgLoA::ViewpointEntropy>(new osgLoA::ViewpointEntropy)->computeBestViews(index, &views);
    const osgLoA::FeatureIndex::Counts counts = index.counts();

    if (o.json)
        std::cout << counts.toJson() << "\n";
    else
    {
        const auto ms = [](auto a, auto b)
        { return std::chrono::duration<double, std::milli>(b - a).count(); };
        std::cout << o.model << ": " << counts.total << " features:";
        for (osgLoA::FeatureType t : osgLoA::kFeatureTypes)
            std::cout << " " << counts.get(t) << " " << osgLoA::toString(t) << ",";
        std::cout << " " << counts.landmarks << " landmarks\n"
                  << "classifier: " << report.summary() << "\n"
                  << std::fixed << std::setprecision(1) << "loaded in " << ms(t0, t1) << " ms, classified in "
                  << ms(t1, t2) << " ms\n";
        if (o.bestViews)
            for (const auto& e : index.entries())
                if (e.feature->getLandmark())
                {
                    const osg::Vec3& d = e.feature->getBestViewDirection();
                    std::cout << "landmark " << e.feature->getId() << " (" << e.feature->getSourceId()
                              << "): ";
                    if (e.feature->hasBestView())
                        std::cout << std::setprecision(3) << "best view from direction " << d.x() << ","
                                  << d.y() << "," << d.z() << " (azimuth " << std::setprecision(0)
                                  << osg::RadiansToDegrees(std::atan2(d.y(), d.x())) << " deg)\n";
                    else
                        std::cout << "no best view (no geometry)\n";
                }
        const std::vector<unsigned> dup = index.duplicateIds();
        if (!dup.empty()) std::cout << "warning: " << dup.size() << " feature ids occur more than once\n";
    }

    if (!o.save.empty()) osgLoA::AtomicFile::writeNode(o.save, *scene);
    if (!o.image.empty())
    {
        osgLoA::FeatureTypeView::apply(index);
        osgLoA::OffscreenRenderer::Settings settings;
        settings.width = o.width;
        settings.height = o.height;
        osg::ref_ptr<osgLoA::OffscreenRenderer> renderer = new osgLoA::OffscreenRenderer(settings);
        renderer->setSceneData(scene.get());
        loa::applyCamera(*renderer, o.camera);
        osgLoA::ImageFile::write(o.image, *renderer->renderImage());
        if (!o.json) std::cout << "wrote " << o.image << "\n";
    }
    if (!o.save.empty() && !o.json) std::cout << "wrote " << o.save << "\n";
    return loa::kOk;
}
} // namespace

int main(int argc, char** argv)
{
    return loa::runTool("loa-classify", [&] { return run(parse(argc, argv)); });
}
