<?xml version="1.0" encoding="UTF-8"?>
<!-- A small CityGML 2.0 city written for osgLoA's tests (MIT): two buildings (one with LoD1 and
     LoD2, one with a BuildingPart), a road, a bridge, a land use area and a plant cover; the
     roof of the first building has an X3D material in the theme "colours". -->
<core:CityModel xmlns:core="http://www.opengis.net/citygml/2.0"
    xmlns:bldg="http://www.opengis.net/citygml/building/2.0"
    xmlns:tran="http://www.opengis.net/citygml/transportation/2.0"
    xmlns:brid="http://www.opengis.net/citygml/bridge/2.0"
    xmlns:luse="http://www.opengis.net/citygml/landuse/2.0"
    xmlns:veg="http://www.opengis.net/citygml/vegetation/2.0"
    xmlns:app="http://www.opengis.net/citygml/appearance/2.0"
    xmlns:gml="http://www.opengis.net/gml"
    xmlns:xlink="http://www.w3.org/1999/xlink">
  <gml:boundedBy>
    <gml:Envelope srsName="EPSG:25832" srsDimension="3">
      <gml:lowerCorner>500000 5400000 0</gml:lowerCorner>
      <gml:upperCorner>500100 5400100 20</gml:upperCorner>
    </gml:Envelope>
  </gml:boundedBy>
  <core:cityObjectMember>
    <bldg:Building gml:id="house">
      <bldg:lod1Solid>
        <gml:Solid>
          <gml:exterior>
            <gml:CompositeSurface>
              <gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">500010 5400010 0 500010 5400020 0 500020 5400020 0 500020 5400010 0 500010 5400010 0</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>
              <gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">500010 5400010 6 500020 5400010 6 500020 5400020 6 500010 5400020 6 500010 5400010 6</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>
              <gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">500010 5400010 0 500020 5400010 0 500020 5400010 6 500010 5400010 6 500010 5400010 0</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>
              <gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">500020 5400010 0 500020 5400020 0 500020 5400020 6 500020 5400010 6 500020 5400010 0</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>
              <gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">500020 5400020 0 500010 5400020 0 500010 5400020 6 500020 5400020 6 500020 5400020 0</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>
              <gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">500010 5400020 0 500010 5400010 0 500010 5400010 6 500010 5400020 6 500010 5400020 0</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>
            </gml:CompositeSurface>
          </gml:exterior>
        </gml:Solid>
      </bldg:lod1Solid>
      <bldg:boundedBy>
        <bldg:WallSurface gml:id="wall-s">
          <bldg:lod2MultiSurface><gml:MultiSurface>
            <gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">500010 5400010 0 500020 5400010 0 500020 5400010 6 500010 5400010 6 500010 5400010 0</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>
            <gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">500020 5400010 0 500020 5400020 0 500020 5400020 6 500020 5400010 6 500020 5400010 0</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>
            <gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">500020 5400020 0 500010 5400020 0 500010 5400020 6 500020 5400020 6 500020 5400020 0</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>
            <gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">500010 5400020 0 500010 5400010 0 500010 5400010 6 500010 5400020 6 500010 5400020 0</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>
          </gml:MultiSurface></bldg:lod2MultiSurface>
        </bldg:WallSurface>
      </bldg:boundedBy>
      <bldg:boundedBy>
        <bldg:RoofSurface gml:id="roof">
          <bldg:lod2MultiSurface><gml:MultiSurface>
            <gml:surfaceMember><gml:Polygon gml:id="roof-polygon"><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">500010 5400010 6 500020 5400010 6 500020 5400020 6 500010 5400020 6 500010 5400010 6</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>
          </gml:MultiSurface></bldg:lod2MultiSurface>
        </bldg:RoofSurface>
      </bldg:boundedBy>
    </bldg:Building>
  </core:cityObjectMember>
  <core:cityObjectMember>
    <bldg:Building gml:id="hall">
      <bldg:lod1MultiSurface><gml:MultiSurface>
        <gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">500050 5400050 8 500070 5400050 8 500070 5400070 8 500050 5400070 8 500050 5400050 8</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>
      </gml:MultiSurface></bldg:lod1MultiSurface>
      <bldg:consistsOfBuildingPart>
        <bldg:BuildingPart gml:id="hall-tower">
          <bldg:lod1MultiSurface><gml:MultiSurface>
            <gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">500070 5400050 20 500075 5400050 20 500075 5400055 20 500070 5400055 20 500070 5400050 20</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>
          </gml:MultiSurface></bldg:lod1MultiSurface>
        </bldg:BuildingPart>
      </bldg:consistsOfBuildingPart>
    </bldg:Building>
  </core:cityObjectMember>
  <core:cityObjectMember>
    <tran:Road gml:id="main-road">
      <tran:lod1MultiSurface><gml:MultiSurface>
        <gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">500000 5400030 0 500100 5400030 0 500100 5400040 0 500000 5400040 0 500000 5400030 0</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>
      </gml:MultiSurface></tran:lod1MultiSurface>
    </tran:Road>
  </core:cityObjectMember>
  <core:cityObjectMember>
    <brid:Bridge gml:id="bridge">
      <brid:lod1MultiSurface><gml:MultiSurface>
        <gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">500080 5400000 3 500090 5400000 3 500090 5400030 3 500080 5400030 3 500080 5400000 3</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>
      </gml:MultiSurface></brid:lod1MultiSurface>
    </brid:Bridge>
  </core:cityObjectMember>
  <core:cityObjectMember>
    <luse:LandUse gml:id="field">
      <luse:lod1MultiSurface><gml:MultiSurface>
        <gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">500000 5400080 0 500040 5400080 0 500040 5400100 0 500000 5400100 0 500000 5400080 0</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>
      </gml:MultiSurface></luse:lod1MultiSurface>
    </luse:LandUse>
  </core:cityObjectMember>
  <core:cityObjectMember>
    <veg:PlantCover gml:id="meadow">
      <veg:lod1MultiSurface><gml:MultiSurface>
        <gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">500050 5400080 0 500090 5400080 0 500090 5400100 0 500050 5400100 0 500050 5400080 0</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>
      </gml:MultiSurface></veg:lod1MultiSurface>
    </veg:PlantCover>
  </core:cityObjectMember>
  <app:appearanceMember>
    <app:Appearance>
      <app:theme>colours</app:theme>
      <app:surfaceDataMember>
        <app:X3DMaterial>
          <app:diffuseColor>0.8 0.1 0.1</app:diffuseColor>
          <app:target>#roof-polygon</app:target>
        </app:X3DMaterial>
      </app:surfaceDataMember>
    </app:Appearance>
  </app:appearanceMember>
</core:CityModel>
