/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/filtering/BilateralFilter>
#include <osgLoA/filtering/ColorQuantizationFilter>
#include <osgLoA/filtering/DoGFilter>
#include <osgLoA/filtering/FilterChain>
#include <osgLoA/styles/TextureAbstraction>

namespace osgLoA
{

namespace
{
osg::ref_ptr<BilateralFilter> bilateral()
{
    osg::ref_ptr<BilateralFilter> b = new BilateralFilter;
    b->setColorSpace(BilateralFilter::LAB);
    b->setSigmaD(3.0f);
    b->setSigmaR(10.0f);
    return b;
}
} // namespace

osg::ref_ptr<ImageFilter> TextureAbstraction::createColorFilter()
{
    osg::ref_ptr<FilterChain> chain = new FilterChain;
    chain->addFilter(bilateral().get());
    chain->addFilter(bilateral().get());
    osg::ref_ptr<ColorQuantizationFilter> q = new ColorQuantizationFilter;
    q->setLevels(8);
    q->setPhiQ(0.7f);
    chain->addFilter(q.get());
    return chain;
}

osg::ref_ptr<ImageFilter> TextureAbstraction::createOutlineFilter()
{
    osg::ref_ptr<FilterChain> chain = new FilterChain;
    chain->addFilter(bilateral().get());
    chain->addFilter(bilateral().get());
    osg::ref_ptr<DoGFilter> dog = new DoGFilter;
    dog->setFlow(false);
    dog->setMode(DoGFilter::EDGES);
    dog->setSigmaE(1.0f);
    dog->setK(1.6f);
    dog->setTau(0.99f);
    dog->setPhi(1.0f);
    dog->setEpsilon(-0.7f);
    chain->addFilter(dog.get());
    return chain;
}

osg::ref_ptr<FilterConfiguration> TextureAbstraction::createConfiguration()
{
    osg::ref_ptr<FilterConfiguration> c = new FilterConfiguration;
    c->setName("texture-abstraction");
    osg::ref_ptr<FilterChannel> colour =
        new FilterChannel("diffuse", 0, kColorUnit, FilterConfiguration::kFilteredDiffuseSampler,
                          FilterConfiguration::kFilteredDiffuseFlag);
    colour->setDefaultFilter(createColorFilter().get());
    c->addChannel(colour.get());
    osg::ref_ptr<FilterChannel> outline =
        new FilterChannel("outline", 0, kOutlineUnit, kOutlineSampler, kOutlineFlag);
    outline->setDefaultFilter(createOutlineFilter().get());
    c->addChannel(outline.get());
    return c;
}

} // namespace osgLoA
