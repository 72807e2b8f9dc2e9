// Filter configurations per texture channel and feature type (paper 000 §4.4): the filter each
// drawable gets follows its feature type, then the channel's default; apply() binds per-level
// filtered textures (the pyramid of MipmapFilter, Eq. 2) on the channel's filtered unit with the
// abstract style's uniforms, or replaces the channel's texture; shared state sets split when their
// owners' types disagree; applying again filters the originals; write-read-write round trips.
#include "support/TestSupport.h"

#include <osgLoA/filtering/FilterConfiguration>
#include <osgLoA/filtering/GaussianFilter>
#include <osgLoA/filtering/MipmapFilter>
#include <osgLoA/semantics/Feature>

#include <osg/Geode>
#include <osg/Geometry>
#include <osg/Texture2D>
#include <osg/Texture3D>
#include <osgDB/ReadFile>
#include <osgDB/WriteFile>

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

using namespace osgLoA;

namespace
{
osg::ref_ptr<GaussianFilter> gaussian(float sigma)
{
    osg::ref_ptr<GaussianFilter> f = new GaussianFilter;
    f->setSigma(sigma);
    return f;
}

/** A 16x16 RGBA8 texture with content at every frequency, repeat-wrapped. */
osg::ref_ptr<osg::Texture2D> texture(const std::string& name, unsigned seed)
{
    FilterImage img(16, 16);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x)
        {
            seed = seed * 1664525u + 1013904223u;
            const float n = float(seed >> 8) / float(1u << 24);
            img.set(x, y, osg::Vec4f((x + y) % 2 ? 0.9f : 0.1f, n, float(x) / 15.0f, 1.0f));
        }
    img.quantize8();
    osg::ref_ptr<osg::Texture2D> t = new osg::Texture2D(img.toImage().get());
    t->setName(name);
    t->setWrap(osg::Texture::WRAP_S, osg::Texture::REPEAT);
    t->setWrap(osg::Texture::WRAP_T, osg::Texture::REPEAT);
    return t;
}

osg::ref_ptr<osg::Geometry> quad(const std::string& name)
{
    osg::ref_ptr<osg::Geometry> g =
        osg::createTexturedQuadGeometry(osg::Vec3(), osg::Vec3(1, 0, 0), osg::Vec3(0, 1, 0));
    g->setName(name);
    return g;
}

/** A feature root (Geode) of that type holding one drawable. */
osg::ref_ptr<osg::Geode> feature(FeatureType type, unsigned id, osg::Drawable* drawable)
{
    osg::ref_ptr<osg::Geode> g = new osg::Geode;
    Feature::attach(*g, new Feature(id, type));
    g->addDrawable(drawable);
    return g;
}

osg::Texture2D* unitTexture(const osg::Drawable& d, unsigned unit)
{
    const osg::StateSet* ss = d.getStateSet();
    return ss ? dynamic_cast<osg::Texture2D*>(const_cast<osg::StateAttribute*>(
                    ss->getTextureAttribute(unit, osg::StateAttribute::TEXTURE)))
              : nullptr;
}

bool flag(const osg::StateSet* ss, const char* name, bool& value)
{
    const osg::Uniform* u = ss ? ss->getUniform(name) : nullptr;
    return u && u->get(value);
}

/** Level 0 of what F gives the texture's image (MipmapFilter's Eq. 2 level 0, 8-bit). */
FilterImage expectedLevel0(const osg::Texture2D& t, const ImageFilter& f)
{
    FilterImage out = f.apply(FilterImage::fromImage(*t.getImage()), ImageBorder::of(t));
    out.quantize8();
    return out;
}

FilterImage level0(const osg::Texture2D& t)
{
    return MipmapFilter::levelsOf(*t.getImage()).front();
}

std::string fileBytes(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}
} // namespace

TEST(FilterConfigurationTest, DefaultChannelsAreDiffuseAndNormal)
{
    osg::ref_ptr<FilterConfiguration> c = FilterConfiguration::createDefault();
    ASSERT_EQ(c->getChannels().size(), 2u);
    const FilterChannel* d = c->getChannel("diffuse");
    ASSERT_TRUE(d);
    EXPECT_EQ(d->getUnit(), 0u);
    EXPECT_EQ(d->getFilteredUnit(), 3);
    EXPECT_EQ(d->getSamplerUniform(), "loa_filteredTexture");
    EXPECT_EQ(d->getFlagUniform(), "loa_hasFilteredTexture");
    EXPECT_EQ(d->getDefaultFilter(), nullptr);
    const FilterChannel* n = c->getChannel("normal");
    ASSERT_TRUE(n);
    EXPECT_EQ(n->getUnit(), 1u);
    EXPECT_EQ(n->getFilteredUnit(), -1);
    EXPECT_EQ(c->getChannel("specular"), nullptr);
}

TEST(FilterConfigurationTest, TheFeatureTypesFilterWinsThenTheDefault)
{
    osg::ref_ptr<FilterChannel> ch = new FilterChannel("diffuse", 0, 3);
    osg::ref_ptr<GaussianFilter> def = gaussian(1.0f), building = gaussian(3.0f);
    EXPECT_EQ(ch->filterFor(FeatureType::Building), nullptr);
    ch->setDefaultFilter(def.get());
    ch->setTypeFilter(FeatureType::Building, building.get());
    ch->setTypeFilter(FeatureType::Water, nullptr); // water: explicitly none
    EXPECT_EQ(ch->filterFor(FeatureType::Building), building.get());
    EXPECT_EQ(ch->filterFor(FeatureType::Water), nullptr);
    EXPECT_TRUE(ch->hasTypeFilter(FeatureType::Water));
    for (FeatureType t :
         {FeatureType::Street, FeatureType::Green, FeatureType::Terrain, FeatureType::Generic})
        EXPECT_EQ(ch->filterFor(t), def.get()) << toString(t);
    ch->clearTypeFilter(FeatureType::Water);
    EXPECT_EQ(ch->filterFor(FeatureType::Water), def.get());
    ch->setFilteredUnit(-7);
    EXPECT_EQ(ch->getFilteredUnit(), -1);
}

TEST(FilterConfigurationTest, ApplyPicksEachDrawablesFilterByItsFeatureType)
{
    // One state set (and texture) shared by a building, a street and a water feature, and a
    // drawable outside every feature; diffuse default sigma 1, buildings sigma 3, water none.
    osg::ref_ptr<osg::Texture2D> wall = texture("wall", 1);
    osg::ref_ptr<osg::StateSet> shared = new osg::StateSet;
    shared->setTextureAttributeAndModes(0, wall.get());
    osg::ref_ptr<osg::Geometry> b = quad("building"), s = quad("street"), w = quad("water"),
                                g = quad("loose"), b2 = quad("building2");
    for (osg::Geometry* d : {b.get(), s.get(), w.get(), g.get(), b2.get()})
        d->setStateSet(shared.get());
    osg::ref_ptr<osg::Group> root = new osg::Group;
    root->addChild(feature(FeatureType::Building, 1, b.get()));
    root->addChild(feature(FeatureType::Building, 2, b2.get()));
    root->addChild(feature(FeatureType::Street, 3, s.get()));
    root->addChild(feature(FeatureType::Water, 4, w.get()));
    osg::ref_ptr<osg::Geode> loose = new osg::Geode;
    loose->addDrawable(g.get());
    root->addChild(loose.get());

    osg::ref_ptr<FilterConfiguration> config = FilterConfiguration::createDefault();
    FilterChannel* diffuse = config->getChannel("diffuse");
    osg::ref_ptr<GaussianFilter> def = gaussian(1.0f), strong = gaussian(3.0f);
    diffuse->setDefaultFilter(def.get());
    diffuse->setTypeFilter(FeatureType::Building, strong.get());
    diffuse->setTypeFilter(FeatureType::Water, nullptr);
    FilterConfiguration::Options options;
    options.threads = 1;
    const FilterConfiguration::Report report = config->apply(*root, options);

    // Three groups: buildings (2 owners, keep the state set), default (street + loose), none (water).
    EXPECT_EQ(report.copiedStateSets, 2u);
    EXPECT_EQ(report.textures, 2u); // the wall filtered once per filter
    EXPECT_EQ(report.stateSets, 2u);
    EXPECT_EQ(report.unfiltered, 1u);
    EXPECT_EQ(b->getStateSet(), shared.get());
    EXPECT_EQ(b2->getStateSet(), shared.get());
    EXPECT_EQ(s->getStateSet(), g->getStateSet());
    EXPECT_NE(s->getStateSet(), shared.get());
    EXPECT_NE(w->getStateSet(), shared.get());
    EXPECT_NE(w->getStateSet(), s->getStateSet());

    // Every drawable still has the original on unit 0; the filtered one on unit 3 per its type.
    for (osg::Geometry* d : {b.get(), s.get(), w.get(), g.get()})
        EXPECT_EQ(unitTexture(*d, 0), wall.get()) << d->getName();
    osg::Texture2D* fb = unitTexture(*b, 3);
    osg::Texture2D* fs = unitTexture(*s, 3);
    ASSERT_TRUE(fb && fs);
    EXPECT_EQ(unitTexture(*w, 3), nullptr);
    EXPECT_LT(FilterImage::maxAbsDifference(level0(*fb), expectedLevel0(*wall, *strong)), 1e-6f);
    EXPECT_LT(FilterImage::maxAbsDifference(level0(*fs), expectedLevel0(*wall, *def)), 1e-6f);
    EXPECT_GT(FilterImage::maxAbsDifference(level0(*fb), level0(*fs)), 0.05f);
    // A full pyramid, sampled trilinearly with the source's wrap modes, at least 16 probes.
    EXPECT_EQ(MipmapFilter::levelsOf(*fb->getImage()).size(), 5u);
    EXPECT_EQ(fb->getWrap(osg::Texture::WRAP_S), osg::Texture::REPEAT);
    EXPECT_EQ(fb->getFilter(osg::Texture::MIN_FILTER), osg::Texture::LINEAR_MIPMAP_LINEAR);
    EXPECT_GE(fb->getMaxAnisotropy(), 16.0f);
    // No fixed-function texturing on the spare unit (it would modulate the fixed-function colour).
    EXPECT_EQ(b->getStateSet()->getTextureMode(3, GL_TEXTURE_2D), osg::StateAttribute::INHERIT);

    bool v = true;
    ASSERT_TRUE(flag(b->getStateSet(), "loa_hasFilteredTexture", v));
    EXPECT_TRUE(v);
    ASSERT_TRUE(flag(s->getStateSet(), "loa_hasFilteredTexture", v));
    EXPECT_TRUE(v);
    ASSERT_TRUE(flag(w->getStateSet(), "loa_hasFilteredTexture", v));
    EXPECT_FALSE(v);
    int unit = 0;
    ASSERT_TRUE(b->getStateSet()->getUniform("loa_filteredTexture"));
    b->getStateSet()->getUniform("loa_filteredTexture")->get(unit);
    EXPECT_EQ(unit, 3);
    // The root's defaults: nothing under it inherits a stale "true".
    ASSERT_TRUE(flag(root->getStateSet(), "loa_hasFilteredTexture", v));
    EXPECT_FALSE(v);
}

TEST(FilterConfigurationTest, FeaturesOnDrawablesAndNestedFeaturesUseTheNearestType)
{
    // A street feature whose group holds a drawable that is itself a building feature, and a
    // drawable without its own feature (the street's).
    osg::ref_ptr<osg::Texture2D> t = texture("t", 2);
    osg::ref_ptr<osg::Geometry> inner = quad("inner"), plain = quad("plain");
    for (osg::Geometry* d : {inner.get(), plain.get()})
        d->getOrCreateStateSet()->setTextureAttributeAndModes(0, t.get());
    Feature::attach(*inner, new Feature(7, FeatureType::Building));
    osg::ref_ptr<osg::Geode> street = feature(FeatureType::Street, 6, plain.get());
    street->addDrawable(inner.get());
    osg::ref_ptr<FilterConfiguration> config = FilterConfiguration::createDefault();
    osg::ref_ptr<GaussianFilter> bf = gaussian(2.0f);
    config->getChannel("diffuse")->setTypeFilter(FeatureType::Building, bf.get());
    config->apply(*street);
    EXPECT_TRUE(unitTexture(*inner, 3));
    EXPECT_FALSE(unitTexture(*plain, 3)); // the street has no filter (no default either)
}

TEST(FilterConfigurationTest, TheNormalChannelIsReplacedAndApplyingAgainFiltersTheOriginal)
{
    osg::ref_ptr<osg::Texture2D> normals = texture("normals", 3);
    osg::ref_ptr<osg::Geometry> d = quad("wall");
    d->getOrCreateStateSet()->setTextureAttributeAndModes(1, normals.get());
    osg::ref_ptr<osg::Geode> root = feature(FeatureType::Building, 1, d.get());
    osg::ref_ptr<FilterConfiguration> config = FilterConfiguration::createDefault();
    osg::ref_ptr<GaussianFilter> f = gaussian(1.5f);
    config->getChannel("normal")->setDefaultFilter(f.get());
    config->apply(*root);
    osg::Texture2D* first = unitTexture(*d, 1);
    ASSERT_TRUE(first);
    EXPECT_NE(first, normals.get());
    EXPECT_EQ(unitTexture(*d, 3), nullptr); // only the diffuse channel uses unit 3
    EXPECT_LT(FilterImage::maxAbsDifference(level0(*first), expectedLevel0(*normals, *f)), 1e-6f);
    osg::Texture* source = FilterConfiguration::sourceTexture(first);
    ASSERT_TRUE(source && source != first);
    EXPECT_EQ(source->getImage(0), normals->getImage());
    // The original keeps its user data untouched.
    EXPECT_EQ(normals->getUserDataContainer(), nullptr);

    // Again: filters the original, not the filtered texture (no double blur).
    const FilterImage once = level0(*first);
    config->apply(*root);
    osg::Texture2D* second = unitTexture(*d, 1);
    ASSERT_TRUE(second);
    EXPECT_LT(FilterImage::maxAbsDifference(level0(*second), once), 1e-6f);
    // Filter none: the original comes back.
    config->getChannel("normal")->setDefaultFilter(nullptr);
    config->apply(*root);
    EXPECT_EQ(unitTexture(*d, 1)->getImage(), normals->getImage());
}

TEST(FilterConfigurationTest, TexturesThatCannotBeFilteredAreReportedAndLeftAlone)
{
    osg::ref_ptr<osg::Geometry> d = quad("volume");
    osg::ref_ptr<osg::Texture3D> t3 = new osg::Texture3D;
    t3->setName("volume");
    d->getOrCreateStateSet()->setTextureAttributeAndModes(0, t3.get());
    osg::ref_ptr<osg::Geometry> e = quad("empty");
    e->getOrCreateStateSet()->setTextureAttributeAndModes(0, new osg::Texture2D); // no image
    osg::ref_ptr<osg::Geode> root = new osg::Geode;
    root->addDrawable(d.get());
    root->addDrawable(e.get());
    osg::ref_ptr<FilterConfiguration> config = FilterConfiguration::createDefault();
    config->getChannel("diffuse")->setDefaultFilter(gaussian(1.0f).get());
    const FilterConfiguration::Report r = config->apply(*root);
    EXPECT_EQ(r.skipped, 2u);
    EXPECT_EQ(r.textures, 0u);
    ASSERT_EQ(r.messages.size(), 2u);
    EXPECT_NE(r.messages[0].find("'volume'"), std::string::npos) << r.messages[0];
    EXPECT_EQ(d->getStateSet()->getTextureAttribute(3, osg::StateAttribute::TEXTURE), nullptr);
}

TEST(FilterConfigurationTest, ConfigurationsSurviveOsgtAndOsgbRoundTrips)
{
    const std::string dir = loatest::freshDirectory("FilterConfigurationTest");
    osg::ref_ptr<FilterConfiguration> config = FilterConfiguration::createDefault();
    config->setName("city");
    FilterChannel* diffuse = config->getChannel("diffuse");
    diffuse->setDefaultFilter(gaussian(1.25f).get());
    diffuse->setTypeFilter(FeatureType::Building, gaussian(4.0f).get());
    diffuse->setTypeFilter(FeatureType::Water, nullptr);
    config->getChannel("normal")->setTypeFilter(FeatureType::Terrain, gaussian(2.0f).get());
    for (const char* ext : {"osgt", "osgb"})
    {
        const std::string first = dir + "/config-first." + ext, second = dir + "/config-second." + ext;
        ASSERT_TRUE(osgDB::writeObjectFile(*config, first)) << first;
        osg::ref_ptr<FilterConfiguration> back =
            dynamic_cast<FilterConfiguration*>(osgDB::readRefObjectFile(first).get());
        ASSERT_TRUE(back.valid()) << first;
        ASSERT_TRUE(osgDB::writeObjectFile(*back, second));
        EXPECT_EQ(fileBytes(first), fileBytes(second)) << ext;
        EXPECT_EQ(back->getName(), "city");
        ASSERT_EQ(back->getChannels().size(), 2u);
        const FilterChannel* d = back->getChannel("diffuse");
        ASSERT_TRUE(d);
        EXPECT_EQ(d->getUnit(), 0u);
        EXPECT_EQ(d->getFilteredUnit(), 3);
        EXPECT_EQ(d->getSamplerUniform(), "loa_filteredTexture");
        EXPECT_EQ(d->getFlagUniform(), "loa_hasFilteredTexture");
        const GaussianFilter* def = dynamic_cast<const GaussianFilter*>(d->getDefaultFilter());
        ASSERT_TRUE(def);
        EXPECT_FLOAT_EQ(def->getSigma(), 1.25f);
        ASSERT_EQ(d->getTypeFilters().size(), 2u);
        const GaussianFilter* bf = dynamic_cast<const GaussianFilter*>(d->filterFor(FeatureType::Building));
        ASSERT_TRUE(bf);
        EXPECT_FLOAT_EQ(bf->getSigma(), 4.0f);
        EXPECT_TRUE(d->hasTypeFilter(FeatureType::Water));
        EXPECT_EQ(d->filterFor(FeatureType::Water), nullptr);
        const FilterChannel* n = back->getChannel("normal");
        ASSERT_TRUE(n);
        EXPECT_EQ(n->getFilteredUnit(), -1);
        EXPECT_TRUE(n->filterFor(FeatureType::Terrain));
        EXPECT_EQ(n->filterFor(FeatureType::Building), nullptr);
    }
    if (::testing::Test::HasFailure()) std::cout << fileBytes(dir + "/config-first.osgt");
}

TEST(FilterConfigurationTest, MalformedFilesFailTheRead)
{
    const std::string dir = loatest::freshDirectory("FilterConfigurationTest-bad");
    osg::ref_ptr<FilterConfiguration> config = FilterConfiguration::createDefault();
    config->getChannel("diffuse")->setTypeFilter(FeatureType::Water, gaussian(1.0f).get());
    ASSERT_TRUE(osgDB::writeObjectFile(*config, dir + "/good.osgt"));
    const std::string good = fileBytes(dir + "/good.osgt");
    const std::size_t at = good.find("\"water\"");
    ASSERT_NE(at, std::string::npos) << good;
    std::string bad = good;
    bad.replace(at, 7, "\"lava\"");
    std::ofstream(dir + "/bad.osgt") << bad;
    EXPECT_FALSE(osgDB::readRefObjectFile(dir + "/bad.osgt").valid());
    // Deep copies clone the filters.
    osg::ref_ptr<FilterConfiguration> deep = new FilterConfiguration(*config, osg::CopyOp::DEEP_COPY_ALL);
    EXPECT_NE(deep->getChannel("diffuse"), config->getChannel("diffuse"));
    EXPECT_NE(deep->getChannel("diffuse")->filterFor(FeatureType::Water),
              config->getChannel("diffuse")->filterFor(FeatureType::Water));
}
