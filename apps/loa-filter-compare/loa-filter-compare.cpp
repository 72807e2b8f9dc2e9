// loa-filter-compare: renders the demo city (or a model) twice with one image filter, once with
// per-level filtered textures (paper 000 Eq. 2: FilterConfiguration + MipmapFilter) and once with
// the filter applied to the rendered frame (Eq. 1: PostProcessFiltering), and writes the two
// images for docs/filtering.md.
#include "../common/AppSupport.h"
#include "../common/CommandLine.h"

#include <osgLoA/city/CityGenerator>
#include <osgLoA/filtering/FilterConfiguration>
#include <osgLoA/filtering/FilterRegistry>
#include <osgLoA/filtering/GpuFilterEngine>
#include <osgLoA/filtering/PostProcessFiltering>
#include <osgLoA/render/HeadlessContext>
#include <osgLoA/render/OffscreenRenderer>
#include <osgLoA/util/ImageFile>
#include <osgLoA/util/StateSetVisitor>

#include <osg/Texture>
#include <osgDB/FileUtils>

#include <iomanip>
#include <iostream>

namespace
{
const char* kDescription =
    R"(Renders the demo city (or MODEL...) with the image filter SPEC ("NAME:key=value,...", see
--list-filters) in two ways and writes, into the --out-dir DIR,
  filtering-NAME-per-level.png     textures filtered per mip level before texture mapping
                                   (paper 000 Eq. 2, perspective-coherent)
  filtering-NAME-post-process.png  the rendered frame filtered (Eq. 1, the baseline)
where NAME is the filter's name (with --name, any other word).
)";
const char* kFooter =
    R"(The camera defaults to "horizon" (the texture gradient of the ground recedes to the horizon).
exit status: 0 done, 1 a filter, model or output failed, 2 bad arguments, 3 no EGL/OpenGL.
)";

struct Options
{
    std::vector<std::string> models;
    std::string filter, out, name, readerOptions;
    int width = loa::kDefaultWidth, height = loa::kDefaultHeight;
    unsigned anisotropy = 16;
    bool cpu = false;
    loa::CameraChoice camera;
};

Options parse(int argc, char** argv)
{
    Options o;
    loa::CommandLine cl("loa-filter-compare",
                        "loa-filter-compare [MODEL...] --filter SPEC --out-dir DIR [options]", kDescription);
    CLI::App& app = cl.app();
    loa::addModels(app, o.models, "the models to render as one scene (default: the demo city)");
    loa::addReaderOptions(app, o.readerOptions);
    loa::addCamera(app, o.camera);
    loa::addSize(app, o.width, o.height, "each image");
    loa::addOutDir(app, o.out, "the output directory (required; created if missing)");
    app.add_option("--filter", o.filter,
                   "the filter (required); it needs GPU passes for the post-process image")
        ->type_name("SPEC");
    app.add_option("--name", o.name, "the NAME in the file names (default: the filter's name)")
        ->type_name("WORD");
    loa::addCount(app, "--anisotropy", o.anisotropy, 1, 16,
                  "anisotropic texture filtering, 1..16 probes, in both images (default 16)");
    app.add_flag("--cpu", o.cpu, "filter the textures with the CPU references instead of the GPU");
    loa::addListFilters(app, "print the registered filters and exit (as loa-prefilter does)");
    cl.footer(kFooter);
    cl.parse(argc, argv);
    if (o.filter.empty()) throw loa::UsageError("--filter SPEC is required");
    if (o.out.empty()) throw loa::UsageError("--out-dir DIR is required");
    loa::checkCameraOptions(o.camera);
    if (o.camera.name.empty() && !o.camera.haveEye) o.camera.name = "horizon";
    if (o.name.find_first_of("/\\ ") != std::string::npos)
        throw loa::UsageError("--name '" + o.name + "' must be one word");
    return o;
}

osg::ref_ptr<osg::Node> scene(const Options& o)
{
    std::string what;
    return loa::loadModelsOrDemoCity(o.models, o.readerOptions, what);
}

/** Every texture of the scene samples with `anisotropy` probes (both images alike). */
void setAnisotropy(osg::Node& node, float anisotropy)
{
    osgLoA::StateSetVisitor v(
        [&](osg::StateSet& ss)
        {
            for (unsigned u = 0; u < ss.getTextureAttributeList().size(); ++u)
                if (auto* t =
                        dynamic_cast<osg::Texture*>(ss.getTextureAttribute(u, osg::StateAttribute::TEXTURE)))
                    t->setMaxAnisotropy(anisotropy);
        });
    node.accept(v);
}

osg::ref_ptr<osg::Image> render(const Options& o, osg::Node* node, const osg::Node& framed)
{
    osgLoA::OffscreenRenderer::Settings s;
    s.width = o.width;
    s.height = o.height;
    osg::ref_ptr<osgLoA::OffscreenRenderer> r = new osgLoA::OffscreenRenderer(s);
    r->setSceneData(node);
    // The camera from the unwrapped scene (the named views look for its features).
    const osgLoA::CameraPose pose =
        loa::cameraPose(o.camera, const_cast<osg::Node&>(framed), double(o.width) / o.height);
    if (!o.camera.name.empty()) r->setPerspective(pose.fovy);
    r->setViewMatrixAsLookAt(pose.eye, pose.center, pose.up);
    return r->renderImage();
}

int run(const Options& o)
{
    osg::ref_ptr<osgLoA::ImageFilter> filter =
        osgLoA::FilterRegistry::create(o.filter); // invalid_argument: 2
    const std::string name = o.name.empty() ? filter->filterName() : o.name;
    if (!filter->hasGpuImplementation())
        throw std::runtime_error("filter '" + filter->filterName() +
                                 "' has no GPU passes: the post-process image cannot be made");
    if (!osgDB::makeDirectory(o.out)) throw std::runtime_error("cannot create the directory '" + o.out + "'");

    // Eq. 2: every texture's pyramid filtered per level (in place of the originals).
    osg::ref_ptr<osg::Node> perLevel = scene(o);
    setAnisotropy(*perLevel, float(o.anisotropy));
    osg::ref_ptr<osgLoA::FilterConfiguration> config = new osgLoA::FilterConfiguration;
    osg::ref_ptr<osgLoA::FilterChannel> diffuse = new osgLoA::FilterChannel("diffuse", 0, -1);
    diffuse->setDefaultFilter(filter.get());
    config->addChannel(diffuse.get());
    osgLoA::FilterConfiguration::Options options;
    options.maxAnisotropy = float(o.anisotropy);
    osg::ref_ptr<osgLoA::HeadlessContext> context;
    osg::ref_ptr<osgLoA::GpuFilterEngine> engine;
    if (!o.cpu)
    {
        context = new osgLoA::HeadlessContext;
        if (!context->realize() || !context->makeCurrent())
            throw osgLoA::HeadlessContextError("the EGL context could not be made current.");
        engine = new osgLoA::GpuFilterEngine(*context->getState());
        options.engine = engine.get();
    }
    const osgLoA::FilterConfiguration::Report report = config->apply(*perLevel, options);
    if (engine.valid())
    {
        engine->releaseGLObjects();
        context->releaseContext();
    }
    for (const std::string& m : report.messages)
        std::cerr << "loa-filter-compare: warning: " << m << "\n";
    osg::ref_ptr<osg::Image> a = render(o, perLevel.get(), *perLevel);

    // Eq. 1: the original scene, the frame filtered.
    osg::ref_ptr<osg::Node> original = scene(o);
    setAnisotropy(*original, float(o.anisotropy));
    osg::ref_ptr<osgLoA::PostProcessFiltering> post = new osgLoA::PostProcessFiltering;
    post->setFilter(filter.get());
    post->setMeasureFilterTime(true);
    post->addChild(original.get());
    osg::ref_ptr<osg::Image> b = render(o, post.get(), *original);
    if (!post->getLastError().empty())
        throw std::runtime_error("post-process filtering: " + post->getLastError());

    const std::string fa = o.out + "/filtering-" + name + "-per-level.png";
    const std::string fb = o.out + "/filtering-" + name + "-post-process.png";
    osgLoA::ImageFile::write(fa, *a);
    osgLoA::ImageFile::write(fb, *b);
    std::cout << std::fixed << std::setprecision(1) << "filter " << filter->getParameterString() << ", "
              << o.width << "x" << o.height << ", " << o.camera.describe() << ", anisotropy " << o.anisotropy
              << "\nper level: " << report.textures << " textures filtered (" << (o.cpu ? "CPU" : "GPU")
              << ") in " << report.milliseconds << " ms\n"
              << "post-process: filter stage " << post->getLastFilterMilliseconds() << " ms (one frame)\n"
              << "wrote " << fa << "\nwrote " << fb << "\n";
    return loa::kOk;
}
} // namespace

int main(int argc, char** argv)
{
    return loa::runTool("loa-filter-compare", [&] { return run(parse(argc, argv)); });
}
