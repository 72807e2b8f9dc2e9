#include <osgLoA/semantics/CityObjectTypes>

namespace osgLoA
{

namespace
{
constexpr FeatureType B = FeatureType::Building, S = FeatureType::Street, W = FeatureType::Water,
                      G = FeatureType::Green, T = FeatureType::Terrain, X = FeatureType::Generic;
} // namespace

const std::vector<CityObjectTypes::Entry>& CityObjectTypes::table()
{
    static const std::vector<Entry> entries = {
        // Buildings (CityGML bldg, CityJSON Building*).
        {"Building", B, "", ""},
        {"BuildingPart", B, "part", ""},
        {"BuildingInstallation", B, "installation",
         "balconies, chimneys, dormers: drawn with their building"},
        {"BuildingConstructiveElement", B, "element", "CityJSON 2.0 / CityGML 3.0"},
        {"BuildingFurniture", B, "furniture", "inside the building"},
        {"BuildingRoom", B, "room", ""},
        {"BuildingStorey", B, "storey", "CityJSON 2.0 / CityGML 3.0"},
        {"BuildingUnit", B, "unit", "CityJSON 2.0 / CityGML 3.0"},
        {"IntBuildingInstallation", B, "installation", "CityGML 1.0/2.0"},
        {"Room", B, "room", "CityGML 1.0/2.0"},
        {"Door", B, "opening", "CityGML opening: drawn with its building"},
        {"Window", B, "opening", "CityGML opening: drawn with its building"},
        {"WallSurface", B, "surface", "CityGML thematic surface: drawn with its building"},
        {"RoofSurface", B, "surface", "CityGML thematic surface: drawn with its building"},
        {"GroundSurface", B, "surface", "CityGML thematic surface: drawn with its building"},
        {"ClosureSurface", B, "surface", "CityGML thematic surface: drawn with its building"},
        {"FloorSurface", B, "surface", "CityGML thematic surface (inside)"},
        {"InteriorWallSurface", B, "surface", "CityGML thematic surface (inside)"},
        {"CeilingSurface", B, "surface", "CityGML thematic surface (inside)"},
        {"OuterCeilingSurface", B, "surface", "CityGML thematic surface: drawn with its building"},
        {"OuterFloorSurface", B, "surface", "CityGML thematic surface: drawn with its building"},
        // Bridges carry traffic: streets, with the sub-type bridge.
        {"Bridge", S, "bridge", "a bridge carries a road or railway: street, sub-type bridge"},
        {"BridgePart", S, "bridge", ""},
        {"BridgeInstallation", S, "bridge", ""},
        {"BridgeConstructiveElement", S, "bridge", ""},
        {"BridgeConstructionElement", S, "bridge", "CityGML 2.0 name"},
        {"BridgeRoom", S, "bridge", ""},
        {"BridgeFurniture", S, "bridge", ""},
        // Transportation.
        {"Road", S, "road", ""},
        {"Railway", S, "railway", ""},
        {"Track", S, "track", "CityGML: a path or field track"},
        {"TransportSquare", S, "square", "CityJSON; CityGML Square"},
        {"Square", S, "square", "CityGML"},
        {"TrafficArea", S, "traffic-area", "CityGML transportation surface"},
        {"AuxiliaryTrafficArea", S, "auxiliary", "CityGML: kerbs, verges, middle strips"},
        {"TransportationObject", S, "", "CityGML: any other transportation object"},
        {"Waterway", W, "waterway", "CityJSON 2.0 / CityGML 3.0 transportation: a navigable water course"},
        // Tunnels carry traffic too.
        {"Tunnel", S, "tunnel", ""},
        {"TunnelPart", S, "tunnel", ""},
        {"TunnelInstallation", S, "tunnel", ""},
        {"TunnelConstructiveElement", S, "tunnel", ""},
        {"TunnelHollowSpace", S, "tunnel", ""},
        {"TunnelFurniture", S, "tunnel", ""},
        // Water.
        {"WaterBody", W, "", "sub-type from the object's class or function attribute where a reader has one"},
        // Vegetation.
        {"PlantCover", G, "plant-cover", ""},
        {"SolitaryVegetationObject", G, "tree", "single trees and bushes"},
        // Relief and land use.
        {"TINRelief", T, "relief", ""},
        {"ReliefFeature", T, "relief", "CityGML"},
        {"MassPointRelief", T, "relief", "CityGML"},
        {"BreaklineRelief", T, "relief", "CityGML"},
        {"RasterRelief", T, "relief", "CityGML"},
        {"ReliefComponent", T, "relief", "CityGML"},
        {"LandUse", T, "land-use",
         "ground of some use; readers refine it from its class or function (grass -> "
         "green, road -> street, water -> water)"},
        // Everything else a city holds.
        {"CityFurniture", X, "furniture", "benches, lamps, signs, traffic lights"},
        {"GenericCityObject", X, "", ""},
        {"OtherConstruction", X, "construction",
         "CityJSON 2.0 / CityGML 3.0: walls, towers, chimneys that "
         "are no buildings"},
        {"CityObjectGroup", X, "group", "a grouping, not a thing"},
    };
    return entries;
}

const CityObjectTypes::Entry* CityObjectTypes::find(const std::string& name)
{
    const std::size_t colon = name.rfind(':');
    const std::string local = colon == std::string::npos ? name : name.substr(colon + 1);
    for (const Entry& e : table())
        if (local == e.name) return &e;
    return nullptr;
}

} // namespace osgLoA
