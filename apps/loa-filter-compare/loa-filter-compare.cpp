// loa-filter-compare: renders the demo city (or a model) twice with one image filter, once with
// per-level filtered textures (paper 000 Eq. 2: FilterConfiguration + MipmapFilter) and once with
// the filter applied to the rendered frame (Eq. 1: PostProcessFiltering), and writes the two
// images for docs/filtering.md.
#include "../common/AppSupport.h"

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
const char* kHelp = R"(usage: loa-filter-compare --filter SPEC --out DIR [options]

Renders the demo city (or MODEL) with the image filter SPEC ("NAME:key=value,...", see
--list-filters) in two ways and writes, into DIR,
  filtering-NAME-per-level.png     textures filtered per mip level before texture mapping
                                   (paper 000 Eq. 2, perspective-coherent)
  filtering-NAME-post-process.png  the rendered frame filtered (Eq. 1, the baseline)
where NAME is the filter's name (with --name, any other word).

options:
  --filter SPEC         the filter (required); it needs GPU passes for the post-process image
  --out DIR             the output directory (required; created if missing)
  --size WxH            image size (default 640x360)
  --name WORD           the NAME in the file names (default: the filter's name)
  --model FILE          render FILE instead of the demo city
  --city "K=V ..."      demo city parameters (docs/demo-city.md)
  --anisotropy N        anisotropic texture filtering, 1..16 probes, in both images (default 16)
  --cpu                 filter the textures with the CPU references instead of the GPU
  --list-filters        print the registered filters and exit (as loa-prefilter does)
)";
const char* kHelpEnd = R"(  --help, --version

The camera defaults to "horizon" (the texture gradient of the ground recedes to the horizon).
exit status: 0 done, 1 a filter, model or output failed, 2 bad arguments, 3 no EGL/OpenGL.
)";

struct Options
{
    std::string filter, out, name, model, city;
    int width = 640, height = 360;
    unsigned anisotropy = 16;
    bool cpu = false;
    loa::CameraChoice camera;
};

Options parse(int argc, char** argv)
{
    Options o;
    loa::Args args(argc, argv);
    while (!args.empty())
    {
        const std::string a = args.next();
        loa::exitOnHelpOrVersion(a, "loa-filter-compare", std::string(kHelp) + loa::kCameraHelp + kHelpEnd);
        if (loa::parseCameraOption(a, args, o.camera))
            continue;
        else if (a == "--filter")
            o.filter = args.value(a);
        else if (a == "--out")
            o.out = args.value(a);
        else if (a == "--size")
            loa::parseSize(args.value(a), o.width, o.height);
        else if (a == "--name")
            o.name = args.value(a);
        else if (a == "--list-filters")
        {
            for (const std::string& n : osgLoA::FilterRegistry::names())
                std::cout << n << "  " << osgLoA::FilterRegistry::description(n) << "\n";
            std::exit(loa::kOk);
        }
        else if (a == "--model")
            o.model = args.value(a);
        else if (a == "--city")
            o.city = args.value(a);
        else if (a == "--anisotropy")
        {
            o.anisotropy = loa::parseCount(a, args.value(a), 16);
            if (o.anisotropy < 1) throw loa::UsageError("--anisotropy must be 1..16");
        }
        else if (a == "--cpu")
            o.cpu = true;
        else
            throw loa::UsageError("unknown option '" + a + "' (see --help)");
    }
    if (o.filter.empty()) throw loa::UsageError("--filter SPEC is required");
    if (o.out.empty()) throw loa::UsageError("--out DIR is required");
    loa::checkCameraOptions(o.camera);
    if (o.camera.name.empty() && !o.camera.haveEye) o.camera.name = "horizon";
    if (o.name.find_first_of("/\\ ") != std::string::npos)
        throw loa::UsageError("--name '" + o.name + "' must be one word");
    return o;
}

osg::ref_ptr<osg::Node> scene(const Options& o)
{
    if (!o.model.empty()) return loa::loadModel(o.model);
    osgLoA::CityParameters params;
    try
    {
        params.parse(o.city);
        params.validate();
    }
    catch (const std::invalid_argument& e)
    {
        throw loa::UsageError(std::string("--city: ") + e.what());
    }
    return osgLoA::CityGenerator(params).generate();
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
