/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/palette/PaletteMapping>
#include <osgLoA/palette/TextureHistogram>
#include <osgLoA/render/ShaderLibrary>

#include <osg/Drawable>
#include <osg/NodeVisitor>
#include <osg/Notify>
#include <osg/Texture2D>
#include <osg/UserDataContainer>

#include <algorithm>
#include <atomic>
#include <exception>
#include <functional>
#include <map>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

namespace osgLoA
{

namespace
{
/** Calls f once for every StateSet of nodes and drawables. */
class EachStateSet : public osg::NodeVisitor
{
public:
    explicit EachStateSet(std::function<void(osg::StateSet&)> f)
        : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN), _f(std::move(f))
    {
    }
    void apply(osg::Node& node) override
    {
        visit(node.getStateSet());
        traverse(node);
    }
    void apply(osg::Drawable& drawable) override { visit(drawable.getStateSet()); }

private:
    void visit(osg::StateSet* ss)
    {
        if (ss && _seen.insert(ss).second) _f(*ss);
    }
    std::function<void(osg::StateSet&)> _f;
    std::set<osg::StateSet*> _seen;
};

const osg::Image* unitZeroImage(const osg::StateSet& ss)
{
    const osg::Texture2D* t =
        dynamic_cast<const osg::Texture2D*>(ss.getTextureAttribute(0, osg::StateAttribute::TEXTURE));
    return t ? t->getImage() : nullptr;
}
} // namespace

unsigned PaletteMapping::attach(osg::Node& scene, const Options& options)
{
    if (options.maxLevels == 0) throw std::invalid_argument("maxLevels: 0; it must be at least 1");
    const std::map<const osg::Image*, std::vector<double>> weights = TextureHistogram::sceneWeights(scene);
    // The textures' palettes are independent (a histogram each, its clustering): built on one
    // thread per core, each job writing only its own slot; the results and the skipped lines
    // are then taken in the map's order, so the outcome does not depend on the threads.
    struct Job
    {
        const osg::Image* image = nullptr;
        const std::vector<double>* weights = nullptr;
        osg::ref_ptr<TexturePalette> palette;
        std::string error;            ///< invalid_argument: the texture is skipped
        std::exception_ptr exception; ///< anything else: rethrown on the calling thread
    };
    std::vector<Job> jobs;
    for (const auto& kv : weights)
    {
        bool any = false;
        for (double w : kv.second)
            any = any || w > 0.0;
        if (!any) continue;
        Job j;
        j.image = kv.first;
        j.weights = &kv.second;
        jobs.push_back(j);
    }
    // Largest first (texels: the histogram's and, roughly, the clustering's work), so that one
    // big texture does not start last.
    std::vector<std::size_t> order(jobs.size());
    for (std::size_t i = 0; i < order.size(); ++i)
        order[i] = i;
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b)
                     {
                         return (long long)(jobs[a].image->s()) * jobs[a].image->t() >
                                (long long)(jobs[b].image->s()) * jobs[b].image->t();
                     });
    std::atomic<std::size_t> next{0};
    auto work = [&]()
    {
        for (std::size_t k = next++; k < jobs.size(); k = next++)
        {
            const std::size_t i = order[k];
            try
            {
                jobs[i].palette = TexturePalette::buildCached(
                    *jobs[i].image, *jobs[i].weights, options.linkage, options.maxLevels, options.cacheDir);
            }
            catch (const std::invalid_argument& e)
            {
                jobs[i].error = e.what();
            }
            catch (...)
            {
                jobs[i].exception = std::current_exception();
            }
        }
    };
    const std::size_t threads =
        std::min<std::size_t>(jobs.size(), std::max(1u, std::thread::hardware_concurrency()));
    std::vector<std::thread> pool;
    for (std::size_t t = 1; t < threads; ++t)
        pool.emplace_back(work);
    work();
    for (std::thread& t : pool)
        t.join();
    for (const Job& j : jobs)
        if (j.exception) std::rethrow_exception(j.exception);
    std::map<const osg::Image*, osg::ref_ptr<TexturePalette>> palettes;
    for (const Job& j : jobs)
    {
        if (j.palette.valid())
        {
            palettes[j.image] = j.palette;
            continue;
        }
        const osg::Image& image = *j.image;
        const std::string line = "palette: skipped texture '" +
                                 (image.getFileName().empty() ? image.getName() : image.getFileName()) +
                                 "': " + j.error;
        OSG_WARN << "osgLoA::PaletteMapping: " << line << std::endl;
        if (options.skipped) options.skipped->push_back(line);
    }
    osg::StateSet* root = scene.getOrCreateStateSet();
    if (!root->getUniform("loa_hasPalette")) root->addUniform(new osg::Uniform("loa_hasPalette", false));
    EachStateSet visitor(
        [&](osg::StateSet& ss)
        {
            const osg::Image* image = unitZeroImage(ss);
            auto it = image ? palettes.find(image) : palettes.end();
            if (it == palettes.end()) return;
            TexturePalette* palette = it->second.get();
            ss.setTextureAttribute(kUnit, palette->getLookupTexture());
            ss.addUniform(new osg::Uniform("loa_paletteLookup", int(kUnit)));
            ss.addUniform(new osg::Uniform("loa_hasPalette", true));
            ss.addUniform(new osg::Uniform("loa_paletteLevels", int(palette->getPaletteImage()->s())));
            osg::UserDataContainer* udc = ss.getOrCreateUserDataContainer();
            for (unsigned i = udc->getNumUserObjects(); i-- > 0;)
                if (dynamic_cast<TexturePalette*>(udc->getUserObject(i))) udc->removeUserObject(i);
            udc->addUserObject(palette);
        });
    scene.accept(visitor);
    return unsigned(palettes.size());
}

unsigned PaletteMapping::attach(osg::Node& scene)
{
    return attach(scene, Options());
}

TexturePalette* PaletteMapping::paletteOf(osg::StateSet& stateSet)
{
    osg::UserDataContainer* udc = stateSet.getUserDataContainer();
    if (!udc) return nullptr;
    for (unsigned i = 0; i < udc->getNumUserObjects(); ++i)
        if (TexturePalette* p = dynamic_cast<TexturePalette*>(udc->getUserObject(i))) return p;
    return nullptr;
}

osg::ref_ptr<osg::Program> PaletteMapping::createProgram()
{
    return ShaderLibrary::createProgram(
        "loa_palette", {"loa_plain.vert.glsl", "loa_palette.frag.glsl", "loa_style_palette.frag.glsl"});
}

} // namespace osgLoA
