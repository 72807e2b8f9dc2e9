/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/semantics/FeatureSubType>
#include <osgLoA/styles/ColorScheme>

namespace osgLoA
{

namespace
{
osg::Vec3f rgb(int r, int g, int b)
{
    return osg::Vec3f(float(r), float(g), float(b)) / 255.0f;
}
} // namespace

const std::vector<ColorScheme::Scheme>& ColorScheme::schemes()
{
    static const std::vector<Scheme> all = []
    {
        std::vector<Scheme> s;
        s.push_back({"feature-types", "one Brewer colour per feature type (no sub-type colours)", {}});
        Scheme b{"brewer-subtypes",
                 "qualitative ColorBrewer colours per sub-type (Set3, Paired, Pastel2): building uses, "
                 "forest kinds, water kinds, road classes",
                 {}};
        FeatureType type = FeatureType::Building;
        auto add = [&](std::initializer_list<const char*> words, const osg::Vec3f& c)
        {
            for (const char* w : words)
                b.colors.push_back({type, w, c});
        };
        // Buildings: Set3 red for homes, orange for commerce, lavender for industry, purple for
        // landmarks.
        add({"residential", "house", "apartments"}, rgb(251, 128, 114));
        add({"commercial"}, rgb(253, 180, 98));
        add({"industrial"}, rgb(190, 186, 218));
        add({"landmark"}, rgb(188, 128, 189));
        type = FeatureType::Green;
        // Green spaces: Paired's light and dark green for broadleaf and needleleaf forest, Set3
        // green for mixed forest, Set3 pale green for lawns, Pastel2 for scrub and cemeteries,
        // Paired light orange for orchards.
        add({"deciduous"}, rgb(178, 223, 138));
        add({"coniferous"}, rgb(51, 160, 44));
        add({"mixed", "forest", "wood", "nature_reserve"}, rgb(179, 222, 105));
        add({"park", "grass", "meadow", "garden", "village_green", "recreation_ground", "grassland", "pitch",
             "golf_course", "playground", "allotments"},
            rgb(204, 235, 197));
        add({"scrub", "heath"}, rgb(230, 245, 201));
        add({"cemetery"}, rgb(179, 226, 205));
        add({"orchard", "vineyard"}, rgb(253, 191, 111));
        type = FeatureType::Water;
        // Water: Paired's light blue for running water, dark blue for canals and the sea, Set3
        // teal for standing water.
        add({"river", "stream", "waterway"}, rgb(166, 206, 227));
        add({"canal", "sea"}, rgb(31, 120, 180));
        add({"lake", "pond", "reservoir"}, rgb(141, 211, 199));
        type = FeatureType::Street;
        // Streets: Set3 orange for major roads, light yellow for minor ones, grey for paths and
        // squares, dark grey for rail.
        add({"major"}, rgb(253, 180, 98));
        add({"minor", "road"}, rgb(255, 255, 179));
        add({"path", "track", "square"}, rgb(217, 217, 217));
        add({"rail", "railway"}, rgb(150, 150, 150));
        s.push_back(b);
        return s;
    }();
    return all;
}

const ColorScheme::Scheme* ColorScheme::find(const std::string& name)
{
    for (const Scheme& s : schemes())
        if (s.name == name) return &s;
    return nullptr;
}

std::string ColorScheme::names()
{
    std::string out;
    for (const Scheme& s : schemes())
        out += (out.empty() ? "" : ", ") + s.name;
    return out;
}

osg::ref_ptr<osg::Uniform> ColorScheme::uniform(const Scheme& scheme)
{
    osg::ref_ptr<osg::Uniform> u =
        new osg::Uniform(osg::Uniform::FLOAT_VEC4, kUniform, FeatureSubType::kCount);
    for (unsigned i = 0; i < unsigned(FeatureSubType::kCount); ++i)
        u->setElement(i, osg::Vec4f(0, 0, 0, 0));
    for (const Scheme::Entry& entry : scheme.colors)
    {
        const int code = FeatureSubType::code(entry.subType);
        if (code > 0) u->setElement(unsigned(code), osg::Vec4f(entry.color, 1.0f + float(int(entry.type))));
    }
    return u;
}

osg::Vec3f ColorScheme::colorOf(const Scheme& scheme, FeatureType type, const std::string& subType,
                                const osg::Vec3f& typeColor)
{
    const int code = FeatureSubType::code(subType);
    if (code <= 0) return typeColor;
    // As the uniform holds it: the last entry of the code wins, for its type only.
    const Scheme::Entry* found = nullptr;
    for (const Scheme::Entry& entry : scheme.colors)
        if (FeatureSubType::code(entry.subType) == code) found = &entry;
    return found && found->type == type ? found->color : typeColor;
}

} // namespace osgLoA
