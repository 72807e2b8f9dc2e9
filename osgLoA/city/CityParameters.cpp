#include <osgLoA/city/CityParameters>

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace osgLoA
{

CityParameters CityParameters::small()
{
    CityParameters p;
    p.blocksX = 4;
    p.blocksY = 3;
    p.terrainResolution = 48;
    p.terrainMargin = 150.0;
    p.landmarks = 2;
    p.parkFraction = 0.17;
    p.forestFraction = 0.17;
    p.forestTreesPerHectare = 120.0;
    return p;
}

CityParameters CityParameters::scaled(double factor) const
{
    CityParameters p = *this;
    p.blocksX = std::max(1, static_cast<int>(std::lround(blocksX * factor)));
    p.blocksY = std::max(1, static_cast<int>(std::lround(blocksY * factor)));
    p.terrainResolution = std::max(8, static_cast<int>(std::lround(terrainResolution * factor)));
    p.landmarks = std::max(0, static_cast<int>(std::lround(landmarks * factor)));
    return p;
}

void CityParameters::validate() const
{
    auto fail = [](const std::string& s) { throw std::invalid_argument("city parameter " + s); };
    if (blocksX < 1 || blocksX > 200) fail("blocksX must be in 1..200");
    if (blocksY < 1 || blocksY > 200) fail("blocksY must be in 1..200");
    if (!(blockSize >= 20.0 && blockSize <= 1000.0)) fail("blockSize must be in 20..1000 m");
    if (!(minorRoadWidth >= 2.0 && minorRoadWidth <= 100.0)) fail("minorRoadWidth must be in 2..100 m");
    if (!(majorRoadWidth >= minorRoadWidth && majorRoadWidth <= 100.0))
        fail("majorRoadWidth must be in minorRoadWidth..100 m");
    if (majorRoadEvery < 1) fail("majorRoadEvery must be at least 1");
    if (terrainResolution < 2 || terrainResolution > 4096) fail("terrainResolution must be in 2..4096");
    if (!(terrainMargin >= 0.0 && terrainMargin <= 10000.0)) fail("terrainMargin must be in 0..10000 m");
    if (!(reliefAmplitude >= 0.0 && reliefAmplitude <= 1000.0)) fail("reliefAmplitude must be in 0..1000 m");
    if (!(riverWidth >= 5.0 && riverWidth <= 3.0 * blockSize)) fail("riverWidth must be in 5 m..3 blockSize");
    if (!(parkFraction >= 0.0 && forestFraction >= 0.0 && parkFraction + forestFraction <= 1.0))
        fail("parkFraction and forestFraction must be non-negative and sum to at most 1");
    if (!(parkTreesPerHectare >= 0.0 && parkTreesPerHectare <= 2000.0))
        fail("parkTreesPerHectare must be in 0..2000");
    if (!(forestTreesPerHectare >= 0.0 && forestTreesPerHectare <= 2000.0))
        fail("forestTreesPerHectare must be in 0..2000");
    if (landmarks < 0 || landmarks > blocksX * blocksY) fail("landmarks must be in 0..blocksX*blocksY");
    if (minFloors < 1 || maxFloors < minFloors || maxFloors > 200)
        fail("floors must satisfy 1 <= minFloors <= maxFloors <= 200");
}

void CityParameters::parse(const std::string& options)
{
    std::string s = options;
    for (char& c : s)
        if (c == ',') c = ' ';
    std::istringstream in(s);
    for (std::string kv; in >> kv;)
    {
        const auto eq = kv.find('=');
        if (eq == std::string::npos) throw std::invalid_argument("city option '" + kv + "' is not key=value");
        const std::string key = kv.substr(0, eq), value = kv.substr(eq + 1);
        std::size_t used = 0;
        double v = 0.0;
        try
        {
            v = std::stod(value, &used);
        }
        catch (const std::exception&)
        {
            used = 0;
        }
        const bool isBool = value == "true" || value == "false";
        if (!isBool && (used != value.size() || value.empty() || !std::isfinite(v)))
            throw std::invalid_argument("city option '" + key + "' has a non-numeric value '" + value + "'");
        auto asInt = [&]()
        {
            if (v != std::floor(v) || std::fabs(v) > 1e9)
                throw std::invalid_argument("city option '" + key + "' needs an integer, not '" + value +
                                            "'");
            return static_cast<int>(v);
        };
        if (key == "seed")
        {
            if (v < 0 || v != std::floor(v) || v > 4294967295.0)
                throw std::invalid_argument("city option 'seed' needs an integer in 0..2^32-1");
            seed = static_cast<unsigned>(v);
        }
        else if (key == "blocksX")
            blocksX = asInt();
        else if (key == "blocksY")
            blocksY = asInt();
        else if (key == "blockSize")
            blockSize = v;
        else if (key == "minorRoadWidth")
            minorRoadWidth = v;
        else if (key == "majorRoadWidth")
            majorRoadWidth = v;
        else if (key == "majorRoadEvery")
            majorRoadEvery = asInt();
        else if (key == "terrainResolution")
            terrainResolution = asInt();
        else if (key == "terrainMargin")
            terrainMargin = v;
        else if (key == "reliefAmplitude")
            reliefAmplitude = v;
        else if (key == "river")
            river = isBool ? value == "true" : v != 0.0;
        else if (key == "riverWidth")
            riverWidth = v;
        else if (key == "parkFraction")
            parkFraction = v;
        else if (key == "forestFraction")
            forestFraction = v;
        else if (key == "parkTreesPerHectare")
            parkTreesPerHectare = v;
        else if (key == "forestTreesPerHectare")
            forestTreesPerHectare = v;
        else if (key == "landmarks")
            landmarks = asInt();
        else if (key == "minFloors")
            minFloors = asInt();
        else if (key == "maxFloors")
            maxFloors = asInt();
        else
            throw std::invalid_argument("unknown city option '" + key + "'");
    }
}

std::string CityParameters::toString() const
{
    std::ostringstream o;
    o << "seed=" << seed << " blocksX=" << blocksX << " blocksY=" << blocksY << " blockSize=" << blockSize
      << " minorRoadWidth=" << minorRoadWidth << " majorRoadWidth=" << majorRoadWidth
      << " majorRoadEvery=" << majorRoadEvery << " terrainResolution=" << terrainResolution
      << " terrainMargin=" << terrainMargin << " reliefAmplitude=" << reliefAmplitude
      << " river=" << (river ? "true" : "false") << " riverWidth=" << riverWidth
      << " parkFraction=" << parkFraction << " forestFraction=" << forestFraction
      << " parkTreesPerHectare=" << parkTreesPerHectare << " forestTreesPerHectare=" << forestTreesPerHectare
      << " landmarks=" << landmarks << " minFloors=" << minFloors << " maxFloors=" << maxFloors;
    return o.str();
}

} // namespace osgLoA
