#include <osgLoA/semantics/FeatureTypeView>

#include <osg/Material>
#include <osg/StateSet>

namespace osgLoA
{

osg::Vec4 FeatureTypeView::colour(FeatureType type)
{
    switch (type)
    {
    case FeatureType::Building:
        return osg::Vec4(0.80f, 0.30f, 0.22f, 1.0f);
    case FeatureType::Street:
        return osg::Vec4(0.50f, 0.50f, 0.50f, 1.0f);
    case FeatureType::Water:
        return osg::Vec4(0.18f, 0.42f, 0.85f, 1.0f);
    case FeatureType::Green:
        return osg::Vec4(0.25f, 0.65f, 0.22f, 1.0f);
    case FeatureType::Terrain:
        return osg::Vec4(0.82f, 0.74f, 0.55f, 1.0f);
    case FeatureType::Generic:
        break;
    }
    return osg::Vec4(0.85f, 0.25f, 0.85f, 1.0f);
}

osg::Vec4 FeatureTypeView::landmarkColour()
{
    return osg::Vec4(1.0f, 0.80f, 0.10f, 1.0f);
}

void FeatureTypeView::apply(const FeatureIndex& index)
{
    const auto forced = osg::StateAttribute::OVERRIDE | osg::StateAttribute::PROTECTED;
    for (const FeatureIndex::Entry& e : index.entries())
    {
        osg::ref_ptr<osg::Node> node;
        if (!e.node.lock(node)) continue;
        osg::ref_ptr<osg::StateSet> ss =
            node->getStateSet() ? new osg::StateSet(*node->getStateSet(), osg::CopyOp::SHALLOW_COPY)
                                : new osg::StateSet;
        const osg::Vec4 c = e.feature->getLandmark() ? landmarkColour() : colour(e.feature->getType());
        osg::ref_ptr<osg::Material> m = new osg::Material;
        m->setColorMode(osg::Material::OFF); // vertex colours do not show through
        m->setDiffuse(osg::Material::FRONT_AND_BACK, c);
        m->setAmbient(osg::Material::FRONT_AND_BACK, c * 0.6f);
        m->setSpecular(osg::Material::FRONT_AND_BACK, osg::Vec4(0, 0, 0, 1));
        ss->setAttributeAndModes(m.get(), osg::StateAttribute::ON | forced);
        for (unsigned unit = 0; unit < 8; ++unit)
        {
            ss->setTextureMode(unit, GL_TEXTURE_1D, osg::StateAttribute::OFF | forced);
            ss->setTextureMode(unit, GL_TEXTURE_2D, osg::StateAttribute::OFF | forced);
            ss->setTextureMode(unit, GL_TEXTURE_3D, osg::StateAttribute::OFF | forced);
        }
        ss->setMode(GL_LIGHTING, osg::StateAttribute::ON | forced);
        node->setStateSet(ss.get());
    }
}

} // namespace osgLoA
