#include <osgLoA/semantics/ClassificationRuleSet>
#include <osgLoA/util/AtomicFile>

#include <osgDB/ReadFile>
#include <osgDB/WriteFile>

#include <cmath>
#include <stdexcept>

namespace osgLoA
{

ClassificationRuleSet::ClassificationRuleSet() {}

ClassificationRuleSet::ClassificationRuleSet(const ClassificationRuleSet& o, const osg::CopyOp& copyop)
    : osg::Object(o, copyop), _overrideModelData(o._overrideModelData), _useAppearance(o._useAppearance),
      _appearanceThreshold(o._appearanceThreshold)
{
    for (const auto& r : o._rules)
        _rules.push_back(copyop.getCopyFlags() & osg::CopyOp::DEEP_COPY_OBJECTS
                             ? new ClassificationRule(*r, copyop)
                             : r.get());
}

void ClassificationRuleSet::validate() const
{
    if (!std::isfinite(_appearanceThreshold) || _appearanceThreshold < 0.0f)
        throw std::invalid_argument(
            "classification rule set: appearance threshold must be a finite Delta E >= 0, got " +
            std::to_string(_appearanceThreshold));
    for (std::size_t i = 0; i < _rules.size(); ++i)
    {
        if (!_rules[i])
            throw std::invalid_argument("classification rule set: rule " + std::to_string(i + 1) +
                                        " is empty");
        try
        {
            _rules[i]->validate();
        }
        catch (const std::invalid_argument& e)
        {
            throw std::invalid_argument("rule " + std::to_string(i + 1) + ": " + e.what());
        }
    }
}

namespace
{
struct DefaultRule
{
    ClassificationRule::Field field;
    ClassificationRule::Syntax syntax;
    const char* pattern;
    FeatureType type;
    const char* subType;
};

using R = ClassificationRule;
constexpr FeatureType B = FeatureType::Building, S = FeatureType::Street, W = FeatureType::Water,
                      G = FeatureType::Green, T = FeatureType::Terrain;

// Order matters within one level of the scene graph: the first rule that matches decides.
// docs/classification.md explains each group.
const DefaultRule kDefaultRules[] = {
    // The importer's object class: CityGML / CityJSON types (exact names).
    {R::IMPORTER_SEMANTICS, R::GLOB, "BuildingPart", B, "part"},
    {R::IMPORTER_SEMANTICS, R::GLOB, "Building*", B, ""},
    {R::IMPORTER_SEMANTICS, R::GLOB, "Road", S, "road"},
    {R::IMPORTER_SEMANTICS, R::GLOB, "Railway", S, "railway"},
    {R::IMPORTER_SEMANTICS, R::GLOB, "TransportSquare", S, "square"},
    {R::IMPORTER_SEMANTICS, R::GLOB, "Tunnel*", S, "tunnel"},
    {R::IMPORTER_SEMANTICS, R::GLOB, "WaterBody", W, ""},
    {R::IMPORTER_SEMANTICS, R::GLOB, "Waterway", W, "waterway"},
    {R::IMPORTER_SEMANTICS, R::GLOB, "PlantCover", G, ""},
    {R::IMPORTER_SEMANTICS, R::GLOB, "SolitaryVegetationObject", G, "tree"},
    {R::IMPORTER_SEMANTICS, R::GLOB, "TINRelief", T, ""},
    {R::IMPORTER_SEMANTICS, R::GLOB, "ReliefFeature", T, ""},
    // OpenStreetMap key=value tags.
    {R::IMPORTER_SEMANTICS, R::GLOB, "building=*", B, ""},
    {R::IMPORTER_SEMANTICS, R::REGEX, "^highway=(motorway|trunk|primary|secondary)", S, "major"},
    {R::IMPORTER_SEMANTICS, R::REGEX, "^highway=", S, "minor"},
    {R::IMPORTER_SEMANTICS, R::REGEX, "^railway=", S, "railway"},
    {R::IMPORTER_SEMANTICS, R::REGEX, "^(natural=water|waterway=|water=|landuse=(reservoir|basin)$)", W, ""},
    {R::IMPORTER_SEMANTICS, R::REGEX, "^(landuse=forest|natural=wood)$", G, "forest"},
    {R::IMPORTER_SEMANTICS, R::REGEX,
     "^(landuse=(grass|meadow|recreation_ground|cemetery|village_green|orchard|vineyard|allotments)|"
     "leisure=(park|garden|pitch|golf_course|playground|nature_reserve)|natural=(scrub|grassland|heath|tree))"
     "$",
     G, ""},
    // CityGML thematic surfaces (drawable names, materials).
    {R::ANY, R::REGEX, "(roof|wall|ground|closure|outerceiling|outerfloor|interiorwall|floor|ceiling)surface",
     B, ""},
    {R::ANY, R::REGEX, "trafficarea", S, ""},
    {R::ANY, R::REGEX, "water(ground|closure)?surface", W, ""},
    // Streets.
    {R::ANY, R::REGEX, "freeway|motorway|highway|expressway|autobahn", S, "major"},
    {R::ANY, R::REGEX, "railroad|railway|tramway", S, "railway"},
    {R::ANY, R::REGEX, "road|street|avenue|boulevard|asphalt|sidewalk|pavement|parking|crosswalk|carriageway",
     S, ""},
    // Water.
    {R::ANY, R::REGEX, "ocean|\\bsea\\b", W, "sea"},
    {R::ANY, R::REGEX, "lake|pond|reservoir", W, "lake"},
    {R::ANY, R::REGEX, "river|stream|creek|brook", W, "river"},
    {R::ANY, R::REGEX, "canal", W, "canal"},
    {R::ANY, R::REGEX, "water", W, ""},
    // Green spaces.
    {R::ANY, R::REGEX, "conifer|pine|spruce|evergreen", G, "coniferous"},
    {R::ANY, R::REGEX, "deciduous|broadleaf|oak|beech|birch|maple", G, "deciduous"},
    {R::ANY, R::REGEX, "mixed.?(forest|wood)", G, "mixed"},
    {R::ANY, R::REGEX, "forest|wood", G, "forest"},
    {R::ANY, R::REGEX, "golf", G, "golfcourse"},
    {R::ANY, R::REGEX, "park", G, "park"},
    {R::ANY, R::REGEX, "cemetery|graveyard", G, "cemetery"},
    {R::ANY, R::REGEX, "garden", G, "garden"},
    {R::ANY, R::REGEX, "grass|lawn|meadow|pasture", G, "grass"},
    {R::ANY, R::REGEX, "scrub|shrub|bush|heath|hedge", G, "scrub"},
    {R::ANY, R::REGEX, "tree|foliage|leaves|vegetation|plantcover", G, ""},
    // Buildings.
    {R::ANY, R::REGEX,
     "building|house|roof|wall|fa(c|\xC3\xA7)ade|tower|church|cathedral|chimney|window|balcony|dwelling|"
     "apartment|"
     "skyscraper|brick",
     B, ""},
    // Terrain and land-use classes drawn as ground.
    {R::ANY, R::REGEX, "urban", T, "urban"},
    {R::ANY, R::REGEX, "residential", T, "residential"},
    {R::ANY, R::REGEX, "industrial", T, "industrial"},
    {R::ANY, R::REGEX, "commercial", T, "commercial"},
    {R::ANY, R::REGEX,
     "terrain|tinrelief|relief|ground|\\bdem\\b|\\bdtm\\b|elevation|heightfield|landscape|soil", T, ""},
};
} // namespace

osg::ref_ptr<ClassificationRuleSet> ClassificationRuleSet::createDefault()
{
    osg::ref_ptr<ClassificationRuleSet> set = new ClassificationRuleSet;
    set->setName("osgLoA default rules");
    for (const DefaultRule& d : kDefaultRules)
        set->addRule(new ClassificationRule(d.field, d.syntax, d.pattern, d.type, d.subType));
    return set;
}

osg::ref_ptr<ClassificationRuleSet> ClassificationRuleSet::read(const std::string& path)
{
    osgDB::ReaderWriter::ReadResult rr = osgDB::Registry::instance()->readObject(path, nullptr);
    if (!rr.validObject())
        throw std::runtime_error(
            "cannot read rule set '" + path + "'" +
            (rr.message().empty() ? std::string(": no reader or file not found") : ": " + rr.message()));
    osg::ref_ptr<ClassificationRuleSet> set = dynamic_cast<ClassificationRuleSet*>(rr.getObject());
    if (!set)
        throw std::runtime_error("'" + path + "' holds a " + std::string(rr.getObject()->className()) +
                                 ", not an osgLoA::ClassificationRuleSet");
    set->validate();
    return set;
}

void ClassificationRuleSet::write(const std::string& path) const
{
    AtomicFile::write(path, [this](const std::string& tmp) { return osgDB::writeObjectFile(*this, tmp); });
}

} // namespace osgLoA
