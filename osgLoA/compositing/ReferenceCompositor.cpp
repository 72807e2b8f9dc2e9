// ReferenceCompositor: the CPU reference of Algorithm 2 with same-surface merging; the GLSL of
// shaders/loa_abuffer_resolve.frag.glsl does the same operations in the same order in float.
#include <osgLoA/compositing/ReferenceCompositor>

#include <algorithm>
#include <cmath>

namespace osgLoA
{

ReferenceCompositor::FragmentList ReferenceCompositor::layers(const FragmentList& fragments) const
{
    FragmentList sorted;
    sorted.reserve(fragments.size());
    for (const Fragment& f : fragments)
        if (f.color.a() > 0.0f) sorted.push_back(f);
    std::stable_sort(sorted.begin(), sorted.end(),
                     [](const Fragment& a, const Fragment& b) { return a.depth < b.depth; });
    if (_mergeEpsilon < 0.0f) return sorted;

    FragmentList merged;
    merged.reserve(sorted.size());
    std::size_t i = 0;
    while (i < sorted.size())
    {
        const float d0 = sorted[i].depth;
        float r = 0.0f, g = 0.0f, b = 0.0f, sumA = 0.0f;
        std::size_t j = i;
        while (j < sorted.size() && sorted[j].depth - d0 <= _mergeEpsilon)
        {
            const osg::Vec4f& c = sorted[j].color;
            r += c.r() * c.a();
            g += c.g() * c.a();
            b += c.b() * c.a();
            sumA += c.a();
            ++j;
        }
        Fragment m;
        m.color.set(r / sumA, g / sumA, b / sumA, std::min(1.0f, sumA));
        m.depth = d0;
        merged.push_back(m);
        i = j;
    }
    return merged;
}

namespace
{
float mixf(float x, float y, float a)
{
    return x * (1.0f - a) + y * a;
}
} // namespace

osg::Vec4f ReferenceCompositor::composite(const FragmentList& fragments) const
{
    const FragmentList l = layers(fragments);
    osg::Vec4f p(0.0f, 0.0f, 0.0f, 0.0f);
    for (std::size_t k = l.size(); k-- > 0;)
    {
        const osg::Vec4f& c = l[k].color;
        p.set(mixf(p.r(), c.r(), c.a()), mixf(p.g(), c.g(), c.a()), mixf(p.b(), c.b(), c.a()),
              mixf(p.a(), 1.0f, c.a()));
    }
    return p;
}

osg::Vec4f ReferenceCompositor::compositeOver(const FragmentList& fragments,
                                              const osg::Vec4f& background) const
{
    const FragmentList l = layers(fragments);
    osg::Vec4f color = background;
    for (std::size_t k = l.size(); k-- > 0;)
    {
        const osg::Vec4f& c = l[k].color;
        color.set(mixf(color.r(), c.r(), c.a()), mixf(color.g(), c.g(), c.a()), mixf(color.b(), c.b(), c.a()),
                  c.a() + color.a() * (1.0f - c.a()));
    }
    return color;
}

std::vector<osg::Vec4f> ReferenceCompositor::compositePremultiplied(const FragmentImage& image) const
{
    std::vector<osg::Vec4f> out;
    out.reserve(image.pixels.size());
    for (const FragmentList& f : image.pixels)
        out.push_back(composite(f));
    return out;
}

osg::ref_ptr<osg::Image> ReferenceCompositor::compositeImage(const FragmentImage& image,
                                                             const osg::Vec4f& background) const
{
    osg::ref_ptr<osg::Image> img = new osg::Image;
    img->allocateImage(image.width, image.height, 1, GL_RGBA, GL_UNSIGNED_BYTE);
    auto byte = [](float v)
    { return static_cast<unsigned char>(std::lround(std::min(1.0f, std::max(0.0f, v)) * 255.0f)); };
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
        {
            const osg::Vec4f c = compositeOver(image.at(x, y), background);
            unsigned char* d = img->data(x, y);
            for (int i = 0; i < 4; ++i)
                d[i] = byte(c[i]);
        }
    return img;
}

ReferenceCompositor::FragmentList ReferenceCompositor::firstInArrivalOrder(const FragmentList& fragments,
                                                                           std::size_t n)
{
    // Fragments with alpha <= 0 are discarded by the shader before the stencil test, so they
    // take no sample.
    FragmentList out;
    for (const Fragment& f : fragments)
    {
        if (out.size() == n) break;
        if (f.color.a() > 0.0f) out.push_back(f);
    }
    return out;
}

ReferenceCompositor::FragmentImage ReferenceCompositor::firstInArrivalOrder(const FragmentImage& image,
                                                                            std::size_t n)
{
    FragmentImage out(image.width, image.height);
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        out.pixels[i] = firstInArrivalOrder(image.pixels[i], n);
    return out;
}

} // namespace osgLoA
