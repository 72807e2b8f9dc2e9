/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/filtering/FilterConfiguration>
#include <osgLoA/filtering/MipmapFilter>
#include <osgLoA/semantics/Feature>

#include <osg/Drawable>
#include <osg/NodeVisitor>
#include <osg/Texture2D>
#include <osg/UserDataContainer>

#include <algorithm>
#include <chrono>
#include <map>
#include <set>
#include <stdexcept>

namespace osgLoA
{

namespace
{
/** The user object a replacing filtered texture keeps its source texture under. */
const char* const kSourceName = "loa.filter.source";

/** A filter's identity for sharing results: class and canonical parameter string. */
/** A texture's name for messages: its own name, else its image's file name, else "unnamed". */
std::string textureName(const osg::Texture2D& t)
{
    if (!t.getName().empty() && t.getName() != kSourceName) return t.getName();
    if (const osg::Image* i = t.getImage())
    {
        if (!i->getFileName().empty()) return i->getFileName();
        if (!i->getName().empty()) return i->getName();
    }
    return "unnamed texture";
}

std::string filterKey(const ImageFilter* f)
{
    return f ? std::string(f->className()) + "|" + f->getParameterString() : std::string();
}

/** Every StateSet owner (node or drawable) with the feature type it belongs to. */
struct Use
{
    osg::Node* owner = nullptr; // a Node or a Drawable (a Node in OSG 3.6)
    FeatureType type = FeatureType::Generic;
};

class OwnerCollector : public osg::NodeVisitor
{
public:
    OwnerCollector() : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN) {}

    void apply(osg::Node& node) override
    {
        const Feature* f = Feature::get(node);
        if (f) _types.push_back(f->getType());
        if (osg::StateSet* ss = node.getStateSet()) record(node, *ss);
        traverse(node);
        if (f) _types.pop_back();
    }
    void apply(osg::Drawable& drawable) override
    {
        const Feature* f = Feature::get(drawable);
        if (osg::StateSet* ss = drawable.getStateSet())
        {
            if (f) _types.push_back(f->getType());
            record(drawable, *ss);
            if (f) _types.pop_back();
        }
    }

    /** State sets in first-met order, each with its owners. */
    std::vector<osg::StateSet*> order;
    std::map<osg::StateSet*, std::vector<Use>> uses;

private:
    void record(osg::Node& owner, osg::StateSet& ss)
    {
        std::vector<Use>& u = uses[&ss];
        if (u.empty()) order.push_back(&ss);
        for (const Use& existing : u)
            if (existing.owner == &owner) return; // met again through another parent path
        u.push_back({&owner, _types.empty() ? FeatureType::Generic : _types.back()});
    }
    std::vector<FeatureType> _types;
};

/** A new uniform each time (replacing any of that name): uniform objects may be shared with
 *  other state sets (a shallow StateSet copy shares them). */
void setBool(osg::StateSet& ss, const std::string& name, bool value)
{
    if (!name.empty()) ss.addUniform(new osg::Uniform(name.c_str(), value));
}

/** Gives a replacing filtered texture its own user data container (a shallow texture copy
 *  shares its source's) holding a shallow copy of the source named kSourceName, so that a later
 *  apply() filters the original again, and a saved scene keeps it. */
void rememberSource(osg::Texture2D& filtered, osg::Texture2D& source)
{
    osg::ref_ptr<osg::UserDataContainer> udc =
        source.getUserDataContainer() ? osg::clone(source.getUserDataContainer(), osg::CopyOp::SHALLOW_COPY)
                                      : new osg::DefaultUserDataContainer;
    const unsigned i = udc->getUserObjectIndex(kSourceName);
    if (i < udc->getNumUserObjects()) udc->removeUserObject(i);
    osg::ref_ptr<osg::Texture2D> named = new osg::Texture2D(source, osg::CopyOp::SHALLOW_COPY);
    named->setUserDataContainer(nullptr);
    named->setName(kSourceName);
    udc->addUserObject(named.get());
    filtered.setUserDataContainer(udc.get());
}

void setSampler(osg::StateSet& ss, const std::string& name, int unit)
{
    if (!name.empty() && unit >= 0) ss.addUniform(new osg::Uniform(name.c_str(), unit));
}
} // namespace

// ---------------------------------------------------------------------------------------------
// FilterChannel

FilterChannel::FilterChannel(const std::string& name, unsigned unit, int filteredUnit,
                             const std::string& samplerUniform, const std::string& flagUniform)
    : _unit(unit), _filteredUnit(filteredUnit < -1 ? -1 : filteredUnit), _samplerUniform(samplerUniform),
      _flagUniform(flagUniform)
{
    setName(name);
}

FilterChannel::FilterChannel(const FilterChannel& other, const osg::CopyOp& copyop)
    : osg::Object(other, copyop), _unit(other._unit), _filteredUnit(other._filteredUnit),
      _samplerUniform(other._samplerUniform), _flagUniform(other._flagUniform),
      _defaultFilter(dynamic_cast<ImageFilter*>(copyop(other._defaultFilter.get())))
{
    for (const auto& kv : other._typeFilters)
        _typeFilters[kv.first] = dynamic_cast<ImageFilter*>(copyop(kv.second.get()));
}

ImageFilter* FilterChannel::filterFor(FeatureType type) const
{
    auto it = _typeFilters.find(type);
    if (it != _typeFilters.end()) return it->second.get();
    return _defaultFilter.get();
}

// ---------------------------------------------------------------------------------------------
// FilterConfiguration

FilterConfiguration::FilterConfiguration(const FilterConfiguration& other, const osg::CopyOp& copyop)
    : osg::Object(other, copyop)
{
    for (const auto& c : other._channels)
        _channels.push_back(dynamic_cast<FilterChannel*>(copyop(c.get())));
}

osg::ref_ptr<FilterConfiguration> FilterConfiguration::createDefault()
{
    osg::ref_ptr<FilterConfiguration> c = new FilterConfiguration;
    c->setName("default");
    c->addChannel(
        new FilterChannel("diffuse", 0, kFilteredDiffuseUnit, kFilteredDiffuseSampler, kFilteredDiffuseFlag));
    c->addChannel(new FilterChannel("normal", 1, -1));
    return c;
}

FilterChannel* FilterConfiguration::getChannel(const std::string& name)
{
    for (auto& c : _channels)
        if (c.valid() && c->getName() == name) return c.get();
    return nullptr;
}

const FilterChannel* FilterConfiguration::getChannel(const std::string& name) const
{
    return const_cast<FilterConfiguration*>(this)->getChannel(name);
}

osg::Texture* FilterConfiguration::sourceTexture(osg::Texture* texture)
{
    if (!texture) return nullptr;
    if (const osg::UserDataContainer* udc = texture->getUserDataContainer())
        if (osg::Texture* source =
                dynamic_cast<osg::Texture*>(const_cast<osg::Object*>(udc->getUserObject(kSourceName))))
            return source;
    return texture;
}

FilterConfiguration::Report FilterConfiguration::apply(osg::Node& scene) const
{
    return apply(scene, Options());
}

FilterConfiguration::Report FilterConfiguration::apply(osg::Node& scene, const Options& options) const
{
    const auto t0 = std::chrono::steady_clock::now();
    Report report;
    std::vector<const FilterChannel*> channels;
    for (const auto& c : _channels)
        if (c.valid()) channels.push_back(c.get());

    // The scene root's defaults: no filtered texture unless a state set says so.
    osg::StateSet* root = scene.getOrCreateStateSet();
    for (const FilterChannel* c : channels)
    {
        setBool(*root, c->getFlagUniform(), false);
        setSampler(*root, c->getSamplerUniform(), c->getFilteredUnit());
    }

    OwnerCollector collector;
    scene.accept(collector);

    // The channel textures a state set has (its own, not inherited), by the original source.
    std::set<const osg::Texture*> reported;
    auto sourceOf = [&](osg::StateSet& ss, const FilterChannel& c) -> osg::Texture2D*
    {
        osg::Texture* t =
            dynamic_cast<osg::Texture*>(ss.getTextureAttribute(c.getUnit(), osg::StateAttribute::TEXTURE));
        if (!t) return nullptr;
        osg::Texture2D* t2 = dynamic_cast<osg::Texture2D*>(sourceTexture(t));
        if (!t2 || !t2->getImage())
        {
            if (reported.insert(t).second)
            {
                ++report.skipped;
                report.messages.push_back("channel '" + c.getName() + "': texture '" + t->getName() + "' (" +
                                          t->className() + ") is not a 2D texture with an image; not filtered");
            }
            return nullptr;
        }
        return t2;
    };

    // How many (source texture, filter) pairs there are, for the progress callback.
    unsigned total = 0;
    if (options.progress)
    {
        std::set<std::pair<osg::Texture2D*, std::string>> pairs;
        for (osg::StateSet* ss : collector.order)
            for (const FilterChannel* c : channels)
                if (osg::Texture2D* source = sourceOf(*ss, *c))
                    for (const Use& u : collector.uses[ss])
                        if (ImageFilter* f = c->filterFor(u.type)) pairs.insert({source, filterKey(f)});
        total = unsigned(pairs.size());
    }
    unsigned done = 0, cached = 0;

    // Filtered textures, one per (source texture, filter); null for a texture MipmapFilter
    // refuses (a compressed or packed image), reported once and left unfiltered.
    std::map<std::pair<osg::Texture2D*, std::string>, osg::ref_ptr<osg::Texture2D>> filtered;
    auto filteredTexture = [&](osg::Texture2D& source, ImageFilter& filter) -> osg::Texture2D*
    {
        auto key = std::make_pair(&source, filterKey(&filter));
        auto it = filtered.find(key);
        if (it != filtered.end()) return it->second.get();
        osg::ref_ptr<MipmapFilter> mf = new MipmapFilter(&filter, options.cache);
        if (options.engine && filter.hasGpuImplementation()) mf->setEngine(options.engine);
        mf->setNumThreads(options.threads);
        osg::ref_ptr<osg::Texture2D> out;
        if (options.progress) options.progress(done, total, textureName(source));
        ++done;
        try
        {
            MipmapFilter::Result result;
            out = mf->filterTexture(source, &result);
            if (result.source == MipmapFilter::CACHE) ++cached;
        }
        catch (const std::invalid_argument& e)
        {
            ++report.skipped;
            report.messages.push_back(textureName(source) + ": " + e.what());
            filtered[key] = nullptr;
            return nullptr;
        }
        const std::string name = source.getName() == kSourceName ? std::string() : source.getName();
        out->setName(filter.filterName() + (name.empty() ? std::string() : " of " + name));
        out->setMaxAnisotropy(std::max(source.getMaxAnisotropy(), options.maxAnisotropy));
        ++report.textures;
        filtered[key] = out;
        return out.get();
    };

    for (osg::StateSet* ss : collector.order)
    {
        std::vector<osg::Texture2D*> sources;
        bool any = false;
        for (const FilterChannel* c : channels)
        {
            sources.push_back(sourceOf(*ss, *c));
            any = any || sources.back();
        }
        if (!any) continue;
        // Owners grouped by the filters they choose, over all channels (a signature).
        std::vector<std::pair<std::string, std::vector<const Use*>>> groups;
        for (const Use& u : collector.uses[ss])
        {
            std::string signature;
            for (std::size_t k = 0; k < channels.size(); ++k)
                signature += filterKey(sources[k] ? channels[k]->filterFor(u.type) : nullptr) + "\n";
            auto g = std::find_if(groups.begin(), groups.end(),
                                  [&](const auto& p) { return p.first == signature; });
            if (g == groups.end())
                groups.push_back({signature, {&u}});
            else
                g->second.push_back(&u);
        }
        // The largest group keeps the state set; the others get a copy each.
        std::stable_sort(groups.begin(), groups.end(),
                         [](const auto& a, const auto& b) { return a.second.size() > b.second.size(); });
        // Copies of the state set as it is, before any group changes it.
        std::vector<osg::ref_ptr<osg::StateSet>> targets(groups.size(), ss);
        for (std::size_t g = 1; g < groups.size(); ++g)
        {
            targets[g] = new osg::StateSet(*ss, osg::CopyOp::SHALLOW_COPY);
            for (const Use* u : groups[g].second)
                u->owner->setStateSet(targets[g].get());
            ++report.copiedStateSets;
        }
        for (std::size_t g = 0; g < groups.size(); ++g)
        {
            osg::StateSet* target = targets[g].get();
            const FeatureType type = groups[g].second.front()->type;
            bool filteredAny = false;
            for (std::size_t k = 0; k < channels.size(); ++k)
            {
                const FilterChannel& c = *channels[k];
                osg::Texture2D* source = sources[k];
                if (!source) continue;
                ImageFilter* filter = c.filterFor(type);
                osg::Texture2D* result = filter ? filteredTexture(*source, *filter) : nullptr;
                if (c.getFilteredUnit() >= 0)
                {
                    if (result)
                        target->setTextureAttribute(unsigned(c.getFilteredUnit()), result);
                    else
                        target->removeTextureAttribute(unsigned(c.getFilteredUnit()),
                                                       osg::StateAttribute::TEXTURE);
                    setSampler(*target, c.getSamplerUniform(), c.getFilteredUnit());
                }
                else
                {
                    if (result) rememberSource(*result, *source);
                    target->setTextureAttribute(c.getUnit(),
                                                result ? static_cast<osg::Texture*>(result) : source);
                }
                setBool(*target, c.getFlagUniform(), result != nullptr);
                filteredAny = filteredAny || result;
            }
            if (filteredAny)
                ++report.stateSets;
            else
                ++report.unfiltered;
        }
    }
    if (options.progress) options.progress(total, total, std::string());
    report.fromCache = cached;
    report.milliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return report;
}

} // namespace osgLoA
