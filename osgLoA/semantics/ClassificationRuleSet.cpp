#include <osgLoA/semantics/CityObjectTypes>
#include <osgLoA/semantics/ClassificationRuleSet>
#include <osgLoA/util/AtomicFile>
#include <osgLoA/util/BoundedObjectReader>

#include <osgDB/FileNameUtils>
#include <osgDB/FileUtils>
#include <osgDB/ReadFile>
#include <osgDB/Registry>
#include <osgDB/WriteFile>

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace osgLoA
{

ClassificationRuleSet::ClassificationRuleSet() {}

ClassificationRuleSet::ClassificationRuleSet(const ClassificationRuleSet& o, const osg::CopyOp& copyop)
    : osg::Object(o, copyop), _overrideModelData(o._overrideModelData), _useAppearance(o._useAppearance),
      _appearanceThreshold(o._appearanceThreshold), _groupObjects(o._groupObjects),
      _mergeTouchingTypes(o._mergeTouchingTypes), _mergeTolerance(o._mergeTolerance)
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
    if (!std::isfinite(_mergeTolerance) || _mergeTolerance < 0.0f)
        throw std::invalid_argument(
            "classification rule set: merge tolerance must be a finite length >= 0, got " +
            std::to_string(_mergeTolerance));
    mergeTouchingTypeList(); // throws for an unknown type name
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

std::vector<FeatureType> ClassificationRuleSet::mergeTouchingTypeList() const
{
    std::vector<FeatureType> out;
    std::istringstream in(_mergeTouchingTypes);
    for (std::string name; in >> name;)
    {
        FeatureType t;
        if (!parseFeatureType(name, t))
            throw std::invalid_argument("classification rule set: merge-touching type '" + name +
                                        "' is not building, street, water, green, terrain or generic");
        out.push_back(t);
    }
    return out;
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
    bool inheritable;
};

using R = ClassificationRule;
constexpr FeatureType B = FeatureType::Building, S = FeatureType::Street, W = FeatureType::Water,
                      G = FeatureType::Green, T = FeatureType::Terrain, X = FeatureType::Generic;
constexpr bool kInherit = true, kOwn = false;

// Order matters within one level of the scene graph: the first rule that matches decides.
// docs/classification.md explains each group. The CityGML / CityJSON object types come first,
// from CityObjectTypes (createDefault).
const DefaultRule kDefaultRules[] = {
    // OpenStreetMap key=value tags.
    {R::IMPORTER_SEMANTICS, R::GLOB, "building=*", B, "", kInherit},
    {R::IMPORTER_SEMANTICS, R::REGEX, "^highway=(motorway|trunk|primary|secondary)", S, "major", kInherit},
    {R::IMPORTER_SEMANTICS, R::REGEX, "^highway=", S, "minor", kInherit},
    {R::IMPORTER_SEMANTICS, R::REGEX, "^railway=", S, "railway", kInherit},
    {R::IMPORTER_SEMANTICS, R::REGEX, "^(natural=water|waterway=|water=|landuse=(reservoir|basin)$)", W, "",
     kInherit},
    {R::IMPORTER_SEMANTICS, R::REGEX, "^(landuse=forest|natural=wood)$", G, "forest", kInherit},
    {R::IMPORTER_SEMANTICS, R::REGEX,
     "^(landuse=(grass|meadow|recreation_ground|cemetery|village_green|orchard|vineyard|allotments)|"
     "leisure=(park|garden|pitch|golf_course|playground|nature_reserve)|natural=(scrub|grassland|heath|tree))"
     "$",
     G, "", kInherit},
    // CityGML thematic surfaces (drawable names, materials: RoofSurface, TrafficArea, ...).
    {R::ANY, R::TOKENS,
     "roof surface|wall surface|ground surface|closure surface|outer ceiling surface|outer floor surface|"
     "interior wall surface|floor surface|ceiling surface",
     B, "", kInherit},
    {R::ANY, R::TOKENS, "traffic area", S, "", kInherit},
    {R::ANY, R::TOKENS, "water surface|water ground surface|water closure surface", W, "", kInherit},
    // Things in a city that are none of the five: vehicles, barriers, street furniture. Before
    // the building words, so that a tire wall is no wall of a house.
    {R::ANY, R::TOKENS,
     "car|truck|lorry|bus|van|vehicle|trailer|tractor|boat|ship|aircraft|airplane|helicopter", X, "vehicle",
     kOwn},
    {R::ANY, R::TOKENS,
     "barrier|guardrail|guard rail|crash barrier|tirewall|tire wall|tyre wall|fence|railing|bollard", X,
     "barrier", kOwn},
    {R::ANY, R::TOKENS,
     "lamp|lamppost|streetlight|street light|street lamp|bench|pylon|signpost|sign|billboard|hydrant|"
     "traffic light|mailbox|bin|antenna",
     X, "furniture", kOwn},
    // Streets.
    {R::ANY, R::TOKENS, "freeway|motorway|highway|expressway|autobahn", S, "major", kInherit},
    {R::ANY, R::TOKENS, "railroad|railway|rail|tramway|tram", S, "railway", kInherit},
    {R::ANY, R::TOKENS, "bridge", S, "bridge", kInherit},
    {R::ANY, R::TOKENS, "tunnel", S, "tunnel", kInherit},
    {R::ANY, R::TOKENS, "curb|kerb", S, "curb", kInherit},
    {R::ANY, R::TOKENS,
     "road|street|avenue|boulevard|lane|asphalt|sidewalk|pavement|parking|crosswalk|carriageway|crossing", S,
     "", kInherit},
    // Water.
    {R::ANY, R::TOKENS, "ocean|sea", W, "sea", kInherit},
    {R::ANY, R::TOKENS, "lake|pond|reservoir|pool", W, "lake", kInherit},
    {R::ANY, R::TOKENS, "river|stream|creek|brook", W, "river", kInherit},
    {R::ANY, R::TOKENS, "canal", W, "canal", kInherit},
    {R::ANY, R::TOKENS, "water|waterway", W, "", kInherit},
    // Green spaces.
    {R::ANY, R::TOKENS, "conifer*|pine|spruce|fir|evergreen", G, "coniferous", kInherit},
    {R::ANY, R::TOKENS, "deciduous|broadleaf|oak|beech|birch|maple|willow|poplar", G, "deciduous", kInherit},
    {R::ANY, R::TOKENS, "mixed forest|mixed wood", G, "mixed", kInherit},
    {R::ANY, R::TOKENS, "forest|wood|woods|woodland", G, "forest", kInherit},
    {R::ANY, R::TOKENS, "golf", G, "golfcourse", kInherit},
    {R::ANY, R::TOKENS, "park", G, "park", kInherit},
    {R::ANY, R::TOKENS, "cemetery|graveyard", G, "cemetery", kInherit},
    {R::ANY, R::TOKENS, "garden", G, "garden", kInherit},
    {R::ANY, R::TOKENS, "grass|grassland|lawn|meadow|pasture|turf", G, "grass", kInherit},
    {R::ANY, R::TOKENS, "scrub|shrub|bush|heath|hedge", G, "scrub", kInherit},
    {R::ANY, R::TOKENS, "tree*|foliage|leaves|leaf|vegetation|plant cover|plantcover", G, "", kInherit},
    // Buildings.
    {R::ANY, R::TOKENS,
     "building|house|roof|wall|facade|fa\xC3\xA7"
     "ade|tower|church|cathedral|chimney|window|balcony|door|"
     "dwelling|apartment|flats|skyscraper|brick|hotel|shop|store|office|garage|barn|shed|storey",
     B, "", kInherit},
    // Land-use classes drawn as ground. Area names: never inherited, or a group called
    // "industrial" would make its buildings and roads terrain.
    {R::ANY, R::TOKENS, "urban", T, "urban", kOwn},
    {R::ANY, R::TOKENS, "residential", T, "residential", kOwn},
    {R::ANY, R::TOKENS, "industrial", T, "industrial", kOwn},
    {R::ANY, R::TOKENS, "commercial", T, "commercial", kOwn},
    {R::ANY, R::TOKENS, "sand|gravel|dirt|soil|rock|earth|mud|snow", T, "", kInherit},
    {R::ANY, R::TOKENS, "terrain|tin relief|tinrelief|relief|dem|dtm|elevation|heightfield|height field", T,
     "", kInherit},
    {R::ANY, R::TOKENS, "ground|landscape", T, "", kOwn},
};
} // namespace

osg::ref_ptr<ClassificationRuleSet> ClassificationRuleSet::createDefault()
{
    osg::ref_ptr<ClassificationRuleSet> set = new ClassificationRuleSet;
    set->setName("osgLoA default rules");
    // The CityGML / CityJSON object types (exact names, CityObjectTypes' table), BuildingPart
    // before Building.
    for (const CityObjectTypes::Entry& e : CityObjectTypes::table())
        set->addRule(new ClassificationRule(ClassificationRule::IMPORTER_SEMANTICS, ClassificationRule::GLOB,
                                            e.name, e.type, e.subType));
    for (const DefaultRule& d : kDefaultRules)
    {
        osg::ref_ptr<ClassificationRule> r =
            new ClassificationRule(d.field, d.syntax, d.pattern, d.type, d.subType);
        r->setInheritable(d.inheritable);
        set->addRule(r.get());
    }
    return set;
}

osg::ref_ptr<ClassificationRuleSet> ClassificationRuleSet::withDefaults(const ClassificationRuleSet& user)
{
    osg::ref_ptr<ClassificationRuleSet> set = new ClassificationRuleSet(user);
    set->setName(user.getName().empty() ? std::string("user rules + osgLoA default rules")
                                        : user.getName() + " + osgLoA default rules");
    const osg::ref_ptr<ClassificationRuleSet> defaults = createDefault();
    for (const auto& r : defaults->getRules())
        set->addRule(r.get());
    return set;
}

osg::ref_ptr<ClassificationRuleSet> ClassificationRuleSet::assemble(const std::vector<std::string>& files,
                                                                    bool rulesOnly, bool overrideModelData)
{
    if (rulesOnly && files.empty())
        throw std::invalid_argument(
            "rules-only needs at least one rule file (the default rules would be dropped)");
    osg::ref_ptr<ClassificationRuleSet> set;
    for (const std::string& f : files)
    {
        osg::ref_ptr<ClassificationRuleSet> user = read(f);
        if (!set)
            set = new ClassificationRuleSet(*user);
        else
            for (const auto& r : user->getRules())
                set->addRule(r.get());
    }
    if (!set)
        set = createDefault();
    else if (!rulesOnly)
        set = withDefaults(*set);
    if (overrideModelData) set->setOverrideModelData(true);
    set->validate();
    return set;
}

osg::ref_ptr<ClassificationRuleSet> ClassificationRuleSet::read(const std::string& path)
{
    const std::string ext = osgDB::getLowerCaseFileExtension(path);
    osg::ref_ptr<osg::Object> object;
    if (BoundedObjectReader::handlesExtension(ext))
    {
        // .osgt and .osgb: read with the work bounded by the file's size (OSG's own readers loop
        // forever on a truncated file and trust the sizes a bit-flipped one states).
        if (osgDB::findDataFile(path).empty())
            throw std::runtime_error("cannot read rule set '" + path + "': file not found");
        try
        {
            object = BoundedObjectReader::readObjectFile(osgDB::findDataFile(path), nullptr);
        }
        catch (const MalformedFileError& e)
        {
            throw std::runtime_error("cannot read rule set '" + path + "': " + e.what());
        }
    }
    else
    {
        osgDB::ReaderWriter::ReadResult rr = osgDB::Registry::instance()->readObject(path, nullptr);
        if (!rr.validObject())
            throw std::runtime_error(
                "cannot read rule set '" + path + "'" +
                (rr.message().empty() ? std::string(": no reader or file not found") : ": " + rr.message()));
        object = rr.getObject();
    }
    return checked(object.get(), path);
}

osg::ref_ptr<ClassificationRuleSet> ClassificationRuleSet::readData(const std::string& data, const std::string& label)
{
    osg::ref_ptr<osg::Object> object;
    try
    {
        object = BoundedObjectReader::readCheckedObject(data, nullptr);
    }
    catch (const MalformedFileError& e)
    {
        throw std::runtime_error("cannot read rule set '" + label + "': " + e.what());
    }
    return checked(object.get(), label);
}

osg::ref_ptr<ClassificationRuleSet> ClassificationRuleSet::checked(osg::Object* object, const std::string& label)
{
    osg::ref_ptr<ClassificationRuleSet> set = dynamic_cast<ClassificationRuleSet*>(object);
    if (!set)
        throw std::runtime_error("'" + label + "' holds a " + std::string(object ? object->className() : "nothing") +
                                 ", not an osgLoA::ClassificationRuleSet");
    set->validate();
    return set;
}

void ClassificationRuleSet::write(const std::string& path) const
{
    AtomicFile::write(path, [this](const std::string& tmp) { return osgDB::writeObjectFile(*this, tmp); });
}

} // namespace osgLoA
