/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/filtering/FilterCache>
#include <osgLoA/palette/PaletteMapping>
#include <osgLoA/styles/GraphicStyleCatalog>
#include <osgLoA/styles/GreenSpaceSignatures>
#include <osgLoA/styles/ObjectSpaceEdges>
#include <osgLoA/styles/StreetPresentation>
#include <osgLoA/styles/StylePreparation>
#include <osgLoA/styles/TextureAbstraction>
#include <osgLoA/styles/TreeSilhouettes>
#include <osgLoA/styles/Waterlining>
#include <osgLoA/transitions/UsageScenario>

#include <osg/Notify>
#include <osg/ValueObject>
#include <osgDB/FileNameUtils>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <sstream>

namespace osgLoA
{

namespace
{
const char* const kKnown[] = {"abstract", "palette", "waterlining", "signatures",
                              "streets",  "trees",   "object-edges"};

/** A style name as its shader files spell it ("object-edges": object_edges). */
std::string shaderWord(std::string style)
{
    std::replace(style.begin(), style.end(), '-', '_');
    return style;
}

std::string join(const std::vector<std::string>& v)
{
    std::string s;
    for (const std::string& x : v)
        s += (s.empty() ? "" : ",") + x;
    return s;
}
} // namespace

std::vector<std::string> StylePreparation::stylesNeeded(const UsageScenario& scenario)
{
    // By the style's fragment shader, so that a user's style made from a built-in one (other
    // parameters, another name) is prepared as the built-in is.
    std::vector<std::string> out;
    for (const char* style : kKnown)
        for (const auto& c : scenario.getConfigurations())
        {
            if (!c.valid()) continue;
            osg::ref_ptr<const GraphicStyle> p = GraphicStyleCatalog::instance().prototype(c->getStyle());
            if (c->getStyle() == style ||
                (p.valid() && p->getFragmentShader() == "loa_style_" + shaderWord(style) + ".frag.glsl"))
            {
                out.push_back(style);
                break;
            }
        }
    return out;
}

std::vector<std::string> StylePreparation::preparedStyles(const osg::Node& model)
{
    std::string value;
    std::vector<std::string> out;
    if (!model.getUserValue(kPreparedKey, value)) return out;
    std::istringstream in(value);
    for (std::string s; std::getline(in, s, ',');)
        if (!s.empty()) out.push_back(s);
    return out;
}

void StylePreparation::Report::add(const Report& other)
{
    styles.insert(styles.end(), other.styles.begin(), other.styles.end());
    palettes += other.palettes;
    waterFeatures += other.waterFeatures;
    abstractTextures += other.abstractTextures;
    abstractFromCache += other.abstractFromCache;
    skipped += other.skipped;
    messages.insert(messages.end(), other.messages.begin(), other.messages.end());
    milliseconds += other.milliseconds;
}

StylePreparation::Report StylePreparation::prepare(osg::Node& model, const UsageScenario& scenario)
{
    return prepare(model, scenario, Options());
}

StylePreparation::Report StylePreparation::prepare(osg::Node& model, const UsageScenario& scenario,
                                                   const Options& options)
{
    const auto t0 = std::chrono::steady_clock::now();
    Report report;
    std::vector<std::string> done = preparedStyles(model);
    bool changed = false;
    auto say = [&](const std::string& line)
    {
        if (options.progress)
            options.progress(line);
        else
            OSG_NOTICE << line << std::endl;
    };
    // The styles with a geometry stage take triangles: quads and polygons made triangles, points
    // and lines (which they cannot draw) counted in a warning. Returns the sets converted.
    auto triangulate = [&](const std::string& style)
    {
        unsigned pointsOrLines = 0;
        const unsigned converted = GraphicStyle::triangulate(model, &pointsOrLines);
        if (pointsOrLines)
        {
            const std::string warn = style + ": " + std::to_string(pointsOrLines) +
                                     " point or line primitive set(s) are not drawn in this style "
                                     "(its geometry stage takes triangles)";
            OSG_WARN << "osgLoA: " << warn << std::endl;
            report.messages.push_back(warn);
        }
        return converted;
    };
    for (const std::string& style : stylesNeeded(scenario))
    {
        if (std::find(done.begin(), done.end(), style) != done.end()) continue;
        if (style == "palette")
        {
            PaletteMapping::Options po;
            std::vector<std::string> skipped;
            po.skipped = &skipped;
            say("osgLoA: palette style: building texture palettes (histograms, hierarchical clustering)");
            report.palettes = PaletteMapping::attach(model, po);
            report.skipped += unsigned(skipped.size());
            report.messages.insert(report.messages.end(), skipped.begin(), skipped.end());
            say("osgLoA: palette style: " + std::to_string(report.palettes) + " texture palette(s) built");
        }
        else if (style == "object-edges")
        {
            // Edge data for the generic features' geometry (ObjectSpaceEdges::prepare).
            const unsigned converted = triangulate(style);
            const ObjectSpaceEdges::Report r = ObjectSpaceEdges::prepare(model);
            say("osgLoA: object-edges: " + std::to_string(r.geometries) + " generic geometries, " +
                std::to_string(r.triangles) + " triangles, " + std::to_string(r.edges) + " edges (" +
                std::to_string(r.boundary) + " boundary, " + std::to_string(r.nonManifold) +
                " non-manifold)" +
                (converted ? ", " + std::to_string(converted) + " quad/polygon sets made triangles"
                           : std::string()));
            if (r.skipped)
                report.messages.push_back("object-edges: " + std::to_string(r.skipped) +
                                          " geometries draw without object-space edges (array types)");
        }
        else if (style == "trees")
        {
            // Triangles for the geometry stage, and the crowns the leaf sprites replace.
            const unsigned converted = triangulate(style);
            if (converted)
                say("osgLoA: trees: " + std::to_string(converted) +
                    " quad/polygon primitive set(s) made triangles");
            const unsigned crowns = TreeSilhouettes::markCrowns(model);
            const std::string line =
                "trees: " + std::to_string(crowns) + " crown drawable(s) marked" +
                (crowns ? "" : ": the model has no tree crowns, trees draws as cartographic");
            if (!crowns)
            {
                OSG_WARN << "osgLoA: " << line << std::endl;
                report.messages.push_back(line);
            }
            else
                say("osgLoA: " + line);
        }
        else if (style == "waterlining" || style == "signatures" || style == "streets")
        {
            // A map over the model's water (shoreline distance), green features (ground) or
            // streets (edge distance).
            const auto start = std::chrono::steady_clock::now();
            const bool water = style == "waterlining", green = style == "signatures";
            unsigned features = 0, triangles = 0;
            std::size_t texels = 0;
            DistanceField::Grid grid;
            if (water)
            {
                const Waterlining::ShoreMap map = Waterlining::attach(model);
                report.waterFeatures += map.waterFeatures;
                features = map.waterFeatures, triangles = map.triangles, texels = map.waterTexels;
                if (map.valid()) grid = map.grid;
            }
            else if (green)
            {
                const GreenSpaceSignatures::GroundMap map = GreenSpaceSignatures::attach(model);
                features = map.greenFeatures, triangles = map.triangles, texels = map.groundTexels;
                if (map.valid()) grid = map.grid;
            }
            else
            {
                const StreetPresentation::StreetMap map = StreetPresentation::attach(model);
                features = map.streetFeatures, triangles = map.triangles, texels = map.streetTexels;
                if (map.valid()) grid = map.grid;
            }
            const char* kind = water ? "water" : green ? "green" : "street";
            if (!grid.valid())
            {
                const std::string line = style + ": the model has no " + kind + " surface (" +
                                         std::to_string(features) + " " + kind + " feature(s)): " +
                                         (water   ? "water draws as cartographic"
                                          : green ? "no symbols are drawn"
                                                  : "streets draw without casings");
                OSG_WARN << "osgLoA: " << line << std::endl;
                report.messages.push_back(line);
            }
            else
            {
                char b[240];
                std::snprintf(
                    b, sizeof b,
                    "osgLoA: %s: %s map of %u %s feature(s), %u triangles: %dx%d texels of %.3g "
                    "units, %zu %s, in %.1f s",
                    style.c_str(),
                    water   ? "shoreline"
                    : green ? "ground"
                            : "edge-distance",
                    features, kind, triangles, grid.width, grid.height, grid.texelSize, texels,
                    water   ? "water"
                    : green ? "on green ground"
                            : "on streets",
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
                say(b);
            }
        }
        else if (style == "abstract" && model.getStateSet() &&
                 model.getStateSet()->getUniform(FilterConfiguration::kFilteredDiffuseFlag))
        {
            // The model carries a FilterConfiguration's filtered textures already (the user's
            // own filters, or a model written after preparation): they are kept.
            done.push_back(style);
            changed = true;
            continue;
        }
        else if (style == "abstract")
        {
            osg::ref_ptr<FilterCache> cache;
            const std::string dir =
                options.cacheDir.empty() ? FilterCache::defaultDirectory() : options.cacheDir;
            if (!dir.empty() && dir != "-") cache = new FilterCache(dir);
            FilterConfiguration::Options fo;
            fo.cache = cache.get();
            fo.threads = options.threads;
            fo.maxAnisotropy = options.maxAnisotropy;
            const auto start = std::chrono::steady_clock::now();
            int lastTenth = -1;
            fo.progress = [&](unsigned n, unsigned total, const std::string& texture)
            {
                if (n == total)
                {
                    char b[160];
                    std::snprintf(
                        b, sizeof b, "%u/%u done in %.1f s", total, total,
                        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
                    say(std::string("osgLoA: abstract style: filtering textures per mip level: ") + b +
                        (cache.valid() ? " (cache " + cache->getDirectory() + ")" : " (no cache)"));
                    return;
                }
                const int tenth = total ? int(10 * n / total) : 0;
                if (tenth == lastTenth) return;
                lastTenth = tenth;
                say("osgLoA: abstract style: filtering textures per mip level: " + std::to_string(n) + "/" +
                    std::to_string(total) + " (" + osgDB::getSimpleFileName(texture) + ")");
            };
            const FilterConfiguration::Report r = TextureAbstraction::createConfiguration()->apply(model, fo);
            report.abstractTextures = r.textures;
            report.abstractFromCache = r.fromCache;
            report.skipped += r.skipped;
            for (const std::string& m : r.messages)
            {
                const std::string line = "abstract style: skipped " + m;
                OSG_WARN << "osgLoA: " << line << std::endl;
                report.messages.push_back(line);
            }
        }
        report.styles.push_back(style);
        done.push_back(style);
        changed = true;
    }
    if (changed) model.setUserValue(kPreparedKey, join(done));
    report.milliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return report;
}

} // namespace osgLoA
