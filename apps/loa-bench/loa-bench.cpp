// loa-bench: named benchmark cases; each writes CSV rows to docs/bench/<case>.csv.
#include "../common/AppSupport.h"
#include "../common/CommandLine.h"
#include "BenchCase.h"

#include <osgLoA/Version>
#include <osgLoA/city/CityGenerator>
#include <osgLoA/render/OffscreenRenderer>
#include <osgLoA/render/ShaderLibrary>
#include <osgLoA/semantics/FeatureClassifier>
#include <osgLoA/semantics/FeatureIndex>
#include <osgLoA/styles/FixedFunctionUniforms>
#include <osgLoA/util/AtomicFile>
#include <osgLoA/util/ImageCompare>
#include <osgLoA/util/MachineInfo>
#include <osgLoA/util/SceneStatistics>

#include <osg/Geometry>
#include <osg/Quat>
#include <osg/Texture>
#include <osg/Uniform>
#include <osgDB/FileNameUtils>
#include <osgDB/FileUtils>
#include <osgDB/ReadFile>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>

namespace
{
const char* kDescription = R"(
Runs benchmark cases headless and writes one CSV per case to DIR/<case>.csv (default
docs/bench), with columns
  case,parameters,frames,median_ms,min_ms,max_ms,error_mean,error_max,machine
Frame times are per frame after one warm-up frame, each frame ended by glFinish. error_* is the
case's accuracy measure (empty when the case has none). scripts/charts draws the charts.

cases:
  plain-render   the demo city from the 'oblique' camera at 800x600, 1280x720, 1920x1080:
                 OSG's default fixed-function pipeline (the baseline every later case is a
                 ratio against) and the project's loa_plain GLSL program
  msaa           the demo city at 1280x720 with 0, 2 and 4 samples: frame time against the
                 mean and max per-pixel error to a 4x-MSAA, 2x2-supersampled reference
  import         load + classify time (ms per repetition, features per second) for the demo
                 city (generated, .osgb, .obj) and the real files found in
                 data/cache/python-osmnx-doc/ (scripts/fetch-test-data), ../shared/data/osm/
                 and ../shared/data/cityjson/ (paths relative to the working directory)
  classify-appearance
                 the appearance-grouping fallback alone: the demo city stripped of features
                 and of every name but one feature in five; classify time against the
                 fraction of drawables typed wrongly (error_mean) and left generic
                 (error_max), for appearance thresholds 0 (same texture only) to 40 Delta E
  classify-objects
                 one real object, one feature: the classifier's object grouping (per Geode,
                 per transform, + touching buildings at 0.05 and 0.5) on TORCS street-1 and
                 the OpenCity block (run from the repository root); classify time against
                 the relative error of the per-type feature counts to the hand counts
                 (error_mean: summed over types, error_max: the worst type)
  interest       ScenarioEvaluator::evaluate per frame (CPU, one thread, no GL) for synthetic
                 grid cities of 1k, 10k and 100k features and the built-in distance, route and
                 view-angle scenarios, the eye circling the centre; error_mean/error_max: the
                 mean and max over five eyes of the fraction of fragment-mode matches flagged
                 mayContribute whose weight is 0 at every point of a dense sampling of the
                 feature's box (draws the conservative flag costs without showing anything)
  distance-field the region-interest distance map (jump flooding, docs/distance-field.md) of a
                 2048 m ground with a route, three circles and a polygon at 512^2, 1024^2 and
                 2048^2 texels: CPU seed rasterization, the CPU exact EDT (Felzenszwalb &
                 Huttenlocher; the reference) and the GPU passes of JFA, 1+JFA and JFA+2 (and
                 1+JFA with the seeds uploaded again each time), ms per computation ended by
                 glFinish; error_mean = mean |error| in texels against the exact EDT,
                 error_max = fraction of texels off by more than one texel

  abuffer        the order-independent transparency methods (docs/abuffer.md) on K = 1..16
                 full-view layers: the stencil-routed A-buffer for N samples and a maximum of
                 routing passes, per-pixel linked lists, weighted blended OIT: ms per frame; error_mean / error_max = mean / max |difference| to the CPU
                 reference compositor, 0..255
  transitions    paper 004's Table 1 on the demo city at 800x600, 1280x720 and 1920x1080:
                 from the oblique camera plain rendering (loa_plain), one homogeneous style
                 (photorealistic, cartographic) through the LoA pipeline and each library
                 scenario; from the street camera plain, both homogeneous styles and the
                 view-distance scenario (whose three levels all show there); on the real test
                 scenes (data/test-scenes) at 1280x720 and 1920x1080 from the street, oblique
                 and top cameras: plain, both homogeneous styles, the distance, view-angle and
                 route scenarios. Each scenario twice: fuse=off (features in transition through
                 the A-buffer; lost = fraction of pixels whose fragments did not all fit it)
                 and fuse=on (fused styles); error of the fused row = its difference from the
                 fuse=off frame (mean, 0..255; fraction of pixels over 16/255)
  cartographic   the cartographic devices of paper 004 §3.2.3 (waterlining, relief, signatures,
                 streets) against flat cartographic, each a homogeneous style through the LoA
                 pipeline, on the demo city and opencity-block at 1280x720 and 1920x1080 from the oblique and
                 top cameras: ms per frame and ratio_to_cartographic (medians of the same run);
                 every frame checked against plain rendering's coverage
  saliency       paper 004 Figure 10 as a number: the share of a spectral-residual saliency
                 map's mass (Hou & Zhang 2007) inside each library scenario's region of
                 interest (its interest debug view, interest > 0.5), homogeneous photorealistic
                 against the scenario, on the demo city and opencity-block, oblique camera,
                 1280x720 and 1920x1080; error_mean = the scenario's share, error_max =
                 photorealistic's
  filters        each image filter of paper 000 on a 512x512 texture: our GPU passes, our
                 CPU reference, OpenCV's implementation where it has one; error = ours
                 against OpenCV (8-bit units)
  filtering      paper 000's Table 1: the demo city along a fly-through with the anisotropic
                 Kuwahara filter in setups 1-4 (per-level cached, per-fragment, per-fragment
                 cached, post-process) at 800x600, 1280x720, 1920x1080; error = last frame
                 against setup 1's (8-bit units)
  abstraction    Table 1 of papers 001 and 002: the demo city in every image-space and
                 hybrid abstraction style (and regular rendering) along a short camera move
                 at 640x480, 800x600, 1280x1024, as ratios to regular rendering; error =
                 mean per-pixel change between consecutive frames (coherence)
  palette        paper 003's palette clustering on real photographs: time against table
                 size (Ward NN-chain, exact centroid) and weighted mean CIELab Delta E
                 against the number of colours, hierarchical against k-means
  preprocess     paper 004's pre-process, bilateral then DoG on every mip level of 1,520
                 textures of 128x128, as textures per second: OpenCV, our GPU, our CPU on all
                 cores, and the flow-based version on the GPU
  viewer         loa-viewer's edit-to-frame latency against scene size (demo cities of 2x2 to
                 16x16 blocks, the real test scenes; 1280x720, oblique): the circle-of-interest
                 scenario, then a fade edit, a region move, a style change and a feature's
                 type change through ScenarioEditor, each with one finished frame, and the
                 fade edit with a full re-bind (ratio_to_rebind); error_mean = mean difference
                 of the frame after the edit to the frame after a full re-bind (8-bit units)

)";

std::vector<Row> plainRender(unsigned frames, std::string& renderer)
{
    std::vector<Row> rows;
    osg::ref_ptr<osg::Node> city = demoCity();
    // The shader variant wraps the same city so both share geometry and textures.
    osg::ref_ptr<osg::Group> shaded = withPlainProgram(city.get());
    const int sizes[3][2] = {{800, 600}, {1280, 720}, {1920, 1080}};
    for (const auto& sz : sizes)
    {
        osg::ref_ptr<osg::Image> fixedFrame;
        for (int pipeline = 0; pipeline < 2; ++pipeline)
        {
            auto r =
                makeRenderer(sz[0], sz[1], 0, pipeline ? static_cast<osg::Node*>(shaded.get()) : city.get());
            renderer = r->getCapabilities().renderer;
            Row row;
            row.parameters = std::to_string(sz[0]) + "x" + std::to_string(sz[1]) +
                             (pipeline ? " pipeline=loa_plain" : " pipeline=fixed");
            row.times = r->timeFrames(frames);
            // The timed frame, checked: the loa_plain program covers what the fixed function does.
            osg::ref_ptr<osg::Image> frame = r->renderImage();
            const std::string problem = pipeline
                                            ? checkFrame(*frame, *fixedFrame, r->getCamera()->getClearColor())
                                            : checkBlocks(*frame, *frame);
            if (!pipeline) fixedFrame = frame;
            row.parameters += " frame=" + (problem.empty() ? std::string("ok") : "FAILED(" + problem + ")");
            row.frameFailed = !problem.empty();
            if (sz[0] == 1920 || row.frameFailed)
                keepFrame(*frame, "plain-render-" + std::to_string(sz[0]) + "x" + std::to_string(sz[1]) +
                                      (pipeline ? "-loa_plain" : "-fixed"));
            rows.push_back(row);
            std::cerr << "  " << row.parameters << ": median " << row.times.median() << " ms\n";
        }
    }
    return rows;
}

/** Box-filters an RGBA image by an integer factor. */
osg::ref_ptr<osg::Image> downsample(const osg::Image& in, int f)
{
    osg::ref_ptr<osg::Image> out = new osg::Image;
    const int w = in.s() / f, h = in.t() / f;
    out->allocateImage(w, h, 1, GL_RGBA, GL_UNSIGNED_BYTE);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 4; ++c)
            {
                int sum = 0;
                for (int j = 0; j < f; ++j)
                    for (int i = 0; i < f; ++i)
                        sum += in.data(x * f + i, y * f + j)[c];
                out->data(x, y)[c] = static_cast<unsigned char>((sum + f * f / 2) / (f * f));
            }
    return out;
}

std::vector<Row> msaa(unsigned frames, std::string& renderer)
{
    std::vector<Row> rows;
    osg::ref_ptr<osg::Node> city = demoCity();
    const int w = 1280, h = 720;
    auto ref = makeRenderer(2 * w, 2 * h, 4, city.get());
    osg::ref_ptr<osg::Image> reference = downsample(*ref->renderImage(), 2);
    for (int samples : {0, 2, 4})
    {
        auto r = makeRenderer(w, h, samples, city.get());
        renderer = r->getCapabilities().renderer;
        Row row;
        row.parameters = "1280x720 samples=" + std::to_string(samples);
        row.times = r->timeFrames(frames);
        osg::ref_ptr<osg::Image> frame = r->renderImage();
        const std::string problem = checkFrame(*frame, *reference, r->getCamera()->getClearColor());
        row.parameters += " frame=" + (problem.empty() ? std::string("ok") : "FAILED(" + problem + ")");
        row.frameFailed = !problem.empty();
        keepFrame(*frame, "msaa-1280x720-samples" + std::to_string(samples));
        const auto cmp = osgLoA::ImageComparison::compare(*frame, *reference, 8);
        std::ostringstream m, x;
        m << std::setprecision(4) << cmp.meanDifference;
        x << cmp.maxDifference;
        row.errorMean = m.str();
        row.errorMax = x.str();
        rows.push_back(row);
        std::cerr << "  " << row.parameters << ": median " << row.times.median() << " ms, mean error "
                  << row.errorMean << "/255\n";
    }
    return rows;
}

double msSince(std::chrono::steady_clock::time_point t0)
{
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

std::vector<std::string> importInputs(const std::string& tmpDir)
{
    std::vector<std::string> inputs = {"demo.loacity"};
    osg::ref_ptr<osg::Node> city = demoCity();
    for (const char* ext : {"osgb", "obj"})
    {
        const std::string path = tmpDir + "/demo-city." + ext;
        osgLoA::AtomicFile::writeNode(path, *city);
        inputs.push_back(path);
    }
    for (const char* dir : {"data/cache/python-osmnx-doc", "../shared/data/osm", "../shared/data/cityjson",
                            "../shared/data/cityjson/rotterdam"})
    {
        osgDB::DirectoryContents files = osgDB::getSortedDirectoryContents(dir);
        for (const std::string& f : files)
        {
            const std::string lower = osgDB::convertToLowerCase(f);
            const bool osm = lower.size() > 4 && (lower.find(".osm") != std::string::npos);
            const bool cityjson = osgDB::getLowerCaseFileExtension(lower) == "json";
            if (osm || cityjson) inputs.push_back(std::string(dir) + "/" + f);
        }
    }
    return inputs;
}

std::vector<Row> import(unsigned frames, std::string& renderer)
{
    renderer = "";
    const std::string tmpDir = "out/bench-import";
    std::vector<Row> rows;
    for (const std::string& input : importInputs(tmpDir))
    {
        Row row;
        std::size_t features = 0;
        double load = 0.0, classify = 0.0;
        for (unsigned i = 0; i < frames; ++i)
        {
            const auto t0 = std::chrono::steady_clock::now();
            osg::ref_ptr<osg::Node> scene = osgDB::readRefNodeFile(input);
            const double l = msSince(t0);
            if (!scene)
            {
                std::cerr << "  " << input << ": cannot be read, skipped\n";
                break;
            }
            const auto t1 = std::chrono::steady_clock::now();
            osgLoA::FeatureClassifier().classify(*scene);
            const double c = msSince(t1);
            features = osgLoA::FeatureIndex(*scene).size();
            row.times.milliseconds.push_back(l + c);
            load += l;
            classify += c;
        }
        if (row.times.milliseconds.empty()) continue;
        const double n = static_cast<double>(row.times.milliseconds.size());
        std::ostringstream p;
        p << std::fixed << std::setprecision(1) << osgDB::getSimpleFileName(input) << " features=" << features
          << " load_ms=" << load / n << " classify_ms=" << classify / n << std::setprecision(0)
          << " features_per_s=" << features / (row.times.median() / 1000.0);
        row.parameters = p.str();
        rows.push_back(row);
        std::cerr << "  " << row.parameters << "\n";
    }
    return rows;
}

// The demo city with its features and names removed, except every fifth feature, which keeps
// its name so that rules classify it; everything else can only be typed by appearance.
struct StrippedCity
{
    osg::ref_ptr<osg::Node> scene;
    std::map<osg::Drawable*, osgLoA::FeatureType> truth;
};

StrippedCity strippedCity()
{
    StrippedCity s;
    s.scene = osgLoA::CityGenerator(osgLoA::CityParameters()).generate();
    struct Strip : osg::NodeVisitor
    {
        Strip() : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN) {}
        osgLoA::FeatureType type = osgLoA::FeatureType::Generic;
        bool keepNames = false;
        StrippedCity* out = nullptr;
        unsigned n = 0;
        void apply(osg::Node& node) override
        {
            const osgLoA::FeatureType saved = type;
            const bool savedKeep = keepNames;
            if (const osgLoA::Feature* f = osgLoA::Feature::get(node))
            {
                type = f->getType();
                keepNames = (n++ % 5) == 0;
                osgLoA::Feature::detach(node);
            }
            if (osg::Drawable* d = node.asDrawable()) out->truth[d] = type;
            if (!keepNames)
            {
                node.setName("");
                if (osg::StateSet* ss = node.getStateSet())
                    for (unsigned u = 0; u < ss->getTextureAttributeList().size(); ++u)
                        if (auto* t = dynamic_cast<osg::Texture*>(
                                ss->getTextureAttribute(u, osg::StateAttribute::TEXTURE)))
                            for (unsigned i = 0; i < t->getNumImages(); ++i)
                                if (osg::Image* img = t->getImage(i))
                                {
                                    img->setName("");
                                    img->setFileName("");
                                }
            }
            traverse(node);
            type = saved;
            keepNames = savedKeep;
        }
    } strip;
    strip.out = &s;
    s.scene->accept(strip);
    return s;
}

std::vector<Row> classifyAppearance(unsigned frames, std::string& renderer)
{
    renderer = "";
    std::vector<Row> rows;
    for (float threshold : {0.0f, 5.0f, 10.0f, 20.0f, 40.0f})
    {
        Row row;
        unsigned wrong = 0, generic = 0, total = 0;
        for (unsigned i = 0; i < frames; ++i)
        {
            StrippedCity city = strippedCity();
            osg::ref_ptr<osgLoA::ClassificationRuleSet> rules =
                osgLoA::ClassificationRuleSet::createDefault();
            rules->setAppearanceThreshold(threshold);
            const auto t0 = std::chrono::steady_clock::now();
            osgLoA::FeatureClassifier(rules.get()).classify(*city.scene);
            row.times.milliseconds.push_back(msSince(t0));
            wrong = generic = total = 0;
            for (const auto& kv : city.truth)
            {
                const osgLoA::Feature* f = nullptr;
                for (osg::Node* p = kv.first; p && !f; p = p->getNumParents() ? p->getParent(0) : nullptr)
                    f = osgLoA::Feature::get(*p);
                ++total;
                if (!f || f->getType() == osgLoA::FeatureType::Generic)
                    ++generic;
                else if (f->getType() != kv.second)
                    ++wrong;
            }
        }
        std::ostringstream p, m, x;
        p << "threshold=" << threshold << " drawables=" << total;
        m << std::setprecision(4) << static_cast<double>(wrong) / total;
        x << std::setprecision(4) << static_cast<double>(generic) / total;
        row.parameters = p.str();
        row.errorMean = m.str();
        row.errorMax = x.str();
        rows.push_back(row);
        std::cerr << "  " << row.parameters << ": median " << row.times.median() << " ms, wrong "
                  << row.errorMean << ", generic " << row.errorMax << "\n";
    }
    return rows;
}

std::string csvQuote(const std::string& s)
{
    std::string q = "\"";
    for (char c : s)
        q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
}
} // namespace

osg::ref_ptr<osg::Node> demoCity()
{
    static osg::ref_ptr<osg::Node> city = osgLoA::CityGenerator(osgLoA::CityParameters()).generate();
    return city;
}

osg::ref_ptr<osgLoA::OffscreenRenderer> makeRenderer(int w, int h, int samples, osg::Node* scene,
                                                     const std::string& camera)
{
    osgLoA::OffscreenRenderer::Settings s;
    s.width = w;
    s.height = h;
    s.samples = samples;
    osg::ref_ptr<osgLoA::OffscreenRenderer> r = new osgLoA::OffscreenRenderer(s);
    r->setSceneData(scene);
    loa::CameraChoice cam;
    cam.name = camera;
    loa::applyCamera(*r, cam);
    return r;
}

std::vector<std::pair<std::string, osg::ref_ptr<osg::Node>>> demoCityAndOpenCityBlock()
{
    std::vector<std::pair<std::string, osg::ref_ptr<osg::Node>>> scenes = {{"demo-city", demoCity()}};
    const std::string block = "data/test-scenes/opencity-block.osgt";
    if (osg::ref_ptr<osg::Node> model = osgDB::fileExists(block) ? osgDB::readRefNodeFile(block) : nullptr)
    {
        osg::ref_ptr<osg::Group> group = new osg::Group;
        group->addChild(model.get());
        osgLoA::FeatureClassifier().classify(*group);
        scenes.push_back({"opencity-block", group});
    }
    else
        std::cerr
            << "  opencity-block: not found (run from the repository root after scripts/fetch-test-data)\n";
    return scenes;
}

double meanChange(const osg::Image& a, const osg::Image& b)
{
    double sum = 0.0;
    const std::size_t n = std::size_t(a.s()) * std::size_t(a.t());
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t c = 0; c < 3; ++c)
            sum += std::fabs(double(a.data()[i * 4 + c]) - double(b.data()[i * 4 + c]));
    return sum / double(n * 3);
}

double temporalChange(osgLoA::OffscreenRenderer& r, unsigned frames)
{
    const osg::Matrixd saved = r.getCamera()->getViewMatrix();
    osg::Vec3d eye, center, up;
    r.getCamera()->getViewMatrixAsLookAt(eye, center, up);
    // getViewMatrixAsLookAt puts the centre at distance 1: the turn is about the vertical through
    // the point looked at, on the ground the cameras aim at.
    const osg::Vec3d dir = center - eye;
    const osg::Vec3d pivot =
        std::fabs(dir.z()) > 1e-9 && eye.z() > 0.0 ? eye + dir * (-eye.z() / dir.z()) : center;
    double change = 0.0;
    osg::ref_ptr<osg::Image> previous;
    for (unsigned i = 0; i < frames; ++i)
    {
        const osg::Quat turn(osg::DegreesToRadians(0.25 * i), osg::Vec3d(0, 0, 1));
        r.setViewMatrixAsLookAt(pivot + turn * (eye - pivot), pivot, turn * up);
        osg::ref_ptr<osg::Image> img = r.renderImage();
        if (previous) change += meanChange(*previous, *img);
        previous = img;
    }
    r.getCamera()->setViewMatrix(saved);
    return frames > 1 ? change / double(frames - 1) : 0.0;
}

osg::ref_ptr<osg::Group> withPlainProgram(osg::Node* scene)
{
    osg::ref_ptr<osg::Group> g = new osg::Group;
    g->addChild(scene);
    g->getOrCreateStateSet()->setAttributeAndModes(
        osgLoA::ShaderLibrary::createProgram("plain", {"loa_plain.vert.glsl", "loa_plain.frag.glsl"}).get());
    g->getOrCreateStateSet()->addUniform(new osg::Uniform("loa_baseTexture", 0));
    // Which drawables have a texture: without it loa_plain samples unit 0 everywhere, and the
    // untextured trees came out black (the frame check of plain-render found them).
    osgLoA::FixedFunctionUniforms::annotate(*scene);
    osgLoA::FixedFunctionUniforms::setDefaults(*g->getOrCreateStateSet());
    return g;
}

int main(int argc, char** argv)
{
    using CaseFn = std::function<std::vector<Row>(unsigned, std::string&)>;
    const std::vector<std::pair<std::string, CaseFn>> cases = {{"plain-render", plainRender},
                                                               {"msaa", msaa},
                                                               {"import", import},
                                                               {"classify-appearance", classifyAppearance},
                                                               {"classify-objects", classifyObjects},
                                                               {"interest", interest},
                                                               {"distance-field", distanceField},
                                                               {"abuffer", abuffer},
                                                               {"transitions", transitions},
                                                               {"cartographic", cartographic},
                                                               {"saliency", saliency},
                                                               {"filters", filters},
                                                               {"preprocess", preprocess},
                                                               {"filtering", filtering},
                                                               {"abstraction", abstraction},
                                                               {"palette", palette},
                                                               {"viewer", viewer}};
    return loa::runTool(
        "loa-bench",
        [&]() -> int
        {
            std::vector<std::string> chosen;
            unsigned frames = 10;
            std::string outDir = "docs/bench";
            bool list = false;
            loa::CommandLine cl("loa-bench",
                                "loa-bench [--case NAME]... [--frames N] [--out-dir DIR] [--list]",
                                kDescription);
            CLI::App& app = cl.app();
            loa::addOutDir(app, outDir, "where the CSVs go (default docs/bench)");
            app.add_option_function<std::vector<std::string>>(
                   "--case",
                   [&](const std::vector<std::string>& names)
                   {
                       for (const std::string& name : names)
                       {
                           bool known = false;
                           for (const auto& c : cases)
                               known = known || c.first == name;
                           if (!known) throw loa::UsageError("unknown case '" + name + "' (see --list)");
                           chosen.push_back(name);
                       }
                   },
                   "run this case (repeatable; default: all)")
                ->type_name("NAME")
                ->allow_extra_args(false);
            loa::addCount(app, "--frames", frames, 1, 10000, "timed frames per configuration (default 10)");
            app.add_flag("--list", list, "list the cases and exit");
            cl.parse(argc, argv);
            if (list)
            {
                for (const auto& c : cases)
                    std::cout << c.first << "\n";
                return loa::kOk;
            }
            const osgLoA::MachineInfo machine = osgLoA::MachineInfo::query();
            std::vector<std::string> failedFrames;
            for (const auto& c : cases)
            {
                if (!chosen.empty() && std::find(chosen.begin(), chosen.end(), c.first) == chosen.end())
                    continue;
                std::cerr << "case " << c.first << " (" << frames << " frames per configuration)\n";
                std::string renderer;
                const std::vector<Row> rows = c.second(frames, renderer);
                const std::string line = machine.line(renderer.empty() ? "none (CPU only)" : renderer);
                std::ostringstream csv;
                csv << std::fixed << std::setprecision(3)
                    << "case,parameters,frames,median_ms,min_ms,max_ms,error_mean,error_max,machine\n";
                for (const Row& r : rows)
                    csv << c.first << "," << csvQuote(r.parameters) << "," << r.times.milliseconds.size()
                        << "," << r.times.median() << "," << r.times.min() << "," << r.times.max() << ","
                        << r.errorMean << "," << r.errorMax << "," << csvQuote(line) << "\n";
                const std::string path = outDir + "/" + c.first + ".csv";
                osgLoA::AtomicFile::writeText(path, csv.str());
                std::cout << "wrote " << path << " (" << rows.size() << " rows; " << line << ")\n";
                for (const Row& r : rows)
                    if (r.frameFailed) failedFrames.push_back(c.first + ": " + r.parameters);
            }
            if (!failedFrames.empty())
            {
                for (const std::string& f : failedFrames)
                    std::cerr << "loa-bench: error: wrong frame in " << f << "\n";
                return 1;
            }
            return loa::kOk;
        });
}
