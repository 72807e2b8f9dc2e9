#include <osgLoA/util/StateSetVisitor>

#include <osg/Drawable>
#include <osg/Texture>

namespace osgLoA
{

StateSetVisitor::StateSetVisitor(std::function<void(osg::StateSet&)> fn)
    : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN), _fn(std::move(fn))
{
}

void StateSetVisitor::apply(osg::Node& node)
{
    if (node.getStateSet()) _fn(*node.getStateSet());
    traverse(node);
}

void StateSetVisitor::apply(osg::Drawable& drawable)
{
    if (drawable.getStateSet()) _fn(*drawable.getStateSet());
}

std::set<osg::Program*> StateSetVisitor::programs(osg::Node& scene)
{
    std::set<osg::Program*> out;
    StateSetVisitor v(
        [&](osg::StateSet& ss)
        {
            if (auto* p = dynamic_cast<osg::Program*>(ss.getAttribute(osg::StateAttribute::PROGRAM)))
                out.insert(p);
        });
    scene.accept(v);
    return out;
}

std::set<osg::Image*> StateSetVisitor::textureImages(osg::Node& scene)
{
    std::set<osg::Image*> out;
    StateSetVisitor v(
        [&](osg::StateSet& ss)
        {
            for (unsigned u = 0; u < ss.getTextureAttributeList().size(); ++u)
                if (auto* t =
                        dynamic_cast<osg::Texture*>(ss.getTextureAttribute(u, osg::StateAttribute::TEXTURE)))
                    for (unsigned i = 0; i < t->getNumImages(); ++i)
                        if (t->getImage(i)) out.insert(t->getImage(i));
        });
    scene.accept(v);
    return out;
}

} // namespace osgLoA
