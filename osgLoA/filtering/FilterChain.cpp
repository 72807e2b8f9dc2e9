/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/filtering/FilterChain>

#include <stdexcept>

namespace osgLoA
{

FilterChain::FilterChain(const FilterChain& other, const osg::CopyOp& copyop) : ImageFilter(other, copyop)
{
    for (const osg::ref_ptr<ImageFilter>& f : other._filters)
        _filters.push_back(copyop.getCopyFlags() & osg::CopyOp::DEEP_COPY_OBJECTS
                               ? static_cast<ImageFilter*>(f->clone(copyop))
                               : f.get());
}

FilterImage FilterChain::apply(const FilterImage& input, const ImageBorder& border) const
{
    FilterImage image = input;
    for (const osg::ref_ptr<ImageFilter>& f : _filters)
        image = f->apply(image, border);
    return image;
}

std::vector<GpuFilterPass> FilterChain::gpuPasses() const
{
    std::vector<GpuFilterPass> all;
    for (const osg::ref_ptr<ImageFilter>& f : _filters)
    {
        std::vector<GpuFilterPass> passes = f->gpuPasses();
        if (passes.empty()) return {};
        const int offset = int(all.size());
        for (GpuFilterPass& p : passes)
        {
            // -1 (this filter's input) is the previous filter's last pass.
            for (int& in : p.inputs)
                in = in < 0 ? offset - 1 : in + offset;
            all.push_back(p);
        }
    }
    return all;
}

bool FilterChain::isInteractive() const
{
    for (const osg::ref_ptr<ImageFilter>& f : _filters)
        if (!f->isInteractive()) return false;
    return true;
}

void FilterChain::checkParameters() const
{
    if (_filters.empty()) throw std::invalid_argument("chain: no filters");
    for (std::size_t i = 0; i < _filters.size(); ++i)
    {
        if (!_filters[i]) throw std::invalid_argument("chain: filter " + std::to_string(i) + " is missing");
        _filters[i]->checkParameters();
    }
}

std::string FilterChain::getChainString() const
{
    std::string s;
    for (const osg::ref_ptr<ImageFilter>& f : _filters)
        s += (s.empty() ? "" : "+") + f->getParameterString();
    return s;
}

} // namespace osgLoA
