// What the fuzz targets share: a scratch path per process, a failure that aborts (libFuzzer
// reports it with the input), the finite-bound promise, and a small fixed city (every feature
// type, a landmark, a nested wood) to classify and evaluate against.
#ifndef OSGLOA_TESTS_FUZZ_FUZZSUPPORT_H
#define OSGLOA_TESTS_FUZZ_FUZZSUPPORT_H 1

#include <osgLoA/semantics/Feature>

#include "../support/BoxGeode.h"

#include <osg/Geode>
#include <osg/Geometry>
#include <osg/Group>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <unistd.h>

namespace fuzz
{

/** TMPDIR (or /tmp)/osgloa-fuzz-PID-NAME. */
inline std::string scratch(const std::string& name)
{
    const char* tmp = std::getenv("TMPDIR");
    return std::string(tmp && *tmp ? tmp : "/tmp") + "/osgloa-fuzz-" + std::to_string(::getpid()) + "-" +
           name;
}

[[noreturn]] inline void fail(const char* target, const std::string& what)
{
    std::fprintf(stderr, "%s: %s\n", target, what.c_str());
    std::abort();
}

/** Issue 22 item 3: nothing infinite reaches the scene graph. */
inline void requireFiniteBound(const char* target, osg::Node& node)
{
    const osg::BoundingSphere bs = node.getBound();
    if (bs.valid() && !(std::isfinite(bs.radius()) && std::isfinite(bs.center().length())))
        fail(target, "the scene's bounding sphere is not finite");
}

inline osg::Geode* addFeature(osg::Group& parent, osgLoA::Feature* f, const osg::Vec3& minimum,
                              const osg::Vec3& maximum)
{
    osg::ref_ptr<osg::Geode> g = loatest::boxGeode(minimum, maximum);
    if (f) osgLoA::Feature::attach(*g, f);
    parent.addChild(g.get());
    return g.get();
}

/** Every feature type, sub-types, a landmark (feature 1, the blueprint scenario's focus
 *  object), a wood of trees (a nested group). With features = false the same geometry without
 *  Feature objects, named as a modeller would name it, for the classifier to work on. */
inline osg::ref_ptr<osg::Group> smallCity(bool features)
{
    using osgLoA::Feature;
    using osgLoA::FeatureType;
    osg::ref_ptr<osg::Group> root = new osg::Group;
    const auto named = [&](const char* name, Feature* f, const osg::Vec3& a, const osg::Vec3& b)
    {
        osg::ref_ptr<Feature> keep = f;
        addFeature(*root, features ? f : nullptr, a, b)->setName(name);
    };
    osg::ref_ptr<Feature> landmark = new Feature(1, FeatureType::Building, "church");
    landmark->setInterest(1.0f);
    landmark->setLod(2.0f);
    named("church", landmark.get(), osg::Vec3(-10, -10, 0), osg::Vec3(10, 10, 40));
    named("house_12", new Feature(2, FeatureType::Building), osg::Vec3(100, 0, 0), osg::Vec3(120, 20, 15));
    named("road_main", new Feature(3, FeatureType::Street, "major"), osg::Vec3(-500, -4, 0),
          osg::Vec3(500, 4, 0.2f));
    named("river", new Feature(4, FeatureType::Water, "river"), osg::Vec3(-500, 200, -1),
          osg::Vec3(500, 260, 0));
    named("terrain", new Feature(5, FeatureType::Terrain), osg::Vec3(-500, -500, -5), osg::Vec3(500, 500, 0));
    named("bench", new Feature(6, FeatureType::Generic), osg::Vec3(-300, -300, 0), osg::Vec3(-299, -299, 3));
    osg::ref_ptr<osg::Group> wood = new osg::Group;
    wood->setName("forest");
    if (features) Feature::attach(*wood, new Feature(7, FeatureType::Green, "mixed forest"));
    root->addChild(wood.get());
    for (unsigned i = 0; i < 4; ++i)
    {
        osg::ref_ptr<Feature> tree =
            new Feature(8 + i, FeatureType::Green, i % 2 ? "coniferous" : "deciduous");
        addFeature(*wood, features ? tree.get() : nullptr, osg::Vec3(300.0f + 10.0f * i, 300, 0),
                   osg::Vec3(304.0f + 10.0f * i, 304, 12))
            ->setName("tree");
    }
    return root;
}

} // namespace fuzz

#endif
