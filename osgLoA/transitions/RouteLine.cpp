// RouteLine: the scenario's regions drawn as lines on the ground (the route on the map).
#include <osgLoA/transitions/RouteLine>

#include <osg/Image>
#include <osg/Math>
#include <osg/Texture2D>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace osgLoA
{

namespace
{
osg::Uniform* routeUniform(osg::StateSet& ss, const char* name, osg::Uniform::Type type)
{
    osg::Uniform* u = ss.getUniform(name);
    if (!u || u->getType() != type)
    {
        osg::ref_ptr<osg::Uniform> created = new osg::Uniform(type, name);
        ss.addUniform(created.get());
        u = created.get();
    }
    return u;
}

void addChain(RouteLine::Segments& out, const std::vector<osg::Vec2d>& points, bool closed,
              const RegionOfInterest& region)
{
    const std::size_t n = points.size();
    for (std::size_t i = 0; i + 1 < n + (closed ? 1 : 0); ++i)
    {
        RouteLine::Segment s;
        s.a = points[i];
        s.b = points[(i + 1) % n];
        s.width = region.getLineWidth();
        s.color = region.getLineColor();
        out.push_back(s);
    }
}
} // namespace

RouteLine::Segments RouteLine::collect(const std::vector<osg::ref_ptr<RegionOfInterest>>& regions)
{
    Segments out;
    for (const auto& r : regions)
    {
        if (!r.valid() || !(r->getLineWidth() > 0.0) || !r->validate().empty()) continue;
        const RegionOfInterest::Vertices& v = r->getVertices();
        switch (r->getShape())
        {
        case RegionOfInterest::POLYLINE:
            if (v.size() >= 2) addChain(out, v, false, *r);
            break;
        case RegionOfInterest::POLYGON:
            if (v.size() >= 3) addChain(out, v, true, *r);
            break;
        case RegionOfInterest::CIRCLES:
            if (r->getRadius() > 0.0)
                for (const osg::Vec2d& c : v)
                {
                    std::vector<osg::Vec2d> ring;
                    for (int k = 0; k < kCircleSegments; ++k)
                    {
                        const double a = 2.0 * osg::PI * k / kCircleSegments;
                        ring.push_back(c + osg::Vec2d(std::cos(a), std::sin(a)) * r->getRadius());
                    }
                    addChain(out, ring, true, *r);
                }
            break;
        }
    }
    return out;
}

void RouteLine::apply(osg::StateSet& ss, const Segments& segments)
{
    if (segments.size() > std::size_t(kMaxSegments))
        throw std::invalid_argument(
            "route line: " + std::to_string(segments.size()) + " segments to draw, more than the " +
            std::to_string(kMaxSegments) +
            " every ground fragment can loop over (simplify the regions drawn as lines, "
            "or set their LineWidth to 0)");
    const int count = int(segments.size());
    const int rows = (count + kTextureWidth - 1) / kTextureWidth;
    routeUniform(ss, "loa_routeLineCount", osg::Uniform::INT)->set(count);
    routeUniform(ss, "loa_routeLineRows", osg::Uniform::INT)->set(rows);
    routeUniform(ss, "loa_routeLines", osg::Uniform::SAMPLER_2D)->set(int(kUnit));
    if (count == 0)
    {
        ss.removeTextureAttribute(kUnit, osg::StateAttribute::TEXTURE);
        return;
    }
    const int width = std::min(count, kTextureWidth);
    osg::ref_ptr<osg::Image> image = new osg::Image;
    image->allocateImage(width, 3 * rows, 1, GL_RGBA, GL_FLOAT);
    image->setInternalTextureFormat(GL_RGBA32F_ARB);
    float* texels = reinterpret_cast<float*>(image->data());
    std::fill(texels, texels + std::size_t(width) * 3 * rows * 4, 0.0f);
    for (int k = 0; k < count; ++k)
    {
        const Segment& s = segments[std::size_t(k)];
        auto texel = [&](int group)
        { return texels + (std::size_t(group * rows + k / width) * width + k % width) * 4; };
        float* g = texel(0);
        g[0] = float(s.a.x());
        g[1] = float(s.a.y());
        g[2] = float(s.b.x());
        g[3] = float(s.b.y());
        float* c = texel(1);
        for (int i = 0; i < 4; ++i)
            c[i] = s.color[i];
        texel(2)[0] = float(s.width);
    }
    osg::ref_ptr<osg::Texture2D> texture = new osg::Texture2D(image.get());
    texture->setName("osgLoA route lines");
    texture->setInternalFormat(GL_RGBA32F_ARB);
    texture->setSourceFormat(GL_RGBA);
    texture->setSourceType(GL_FLOAT);
    texture->setFilter(osg::Texture::MIN_FILTER, osg::Texture::NEAREST);
    texture->setFilter(osg::Texture::MAG_FILTER, osg::Texture::NEAREST);
    texture->setResizeNonPowerOfTwoHint(false);
    texture->setUseHardwareMipMapGeneration(false);
    ss.setTextureAttribute(kUnit, texture.get());
}

RouteLine::Nearest RouteLine::nearest(const Segments& segments, const osg::Vec3d& p,
                                      const osg::Matrixd& sceneToClip, const osg::Vec2d& pixelsPerNdc)
{
    auto clip = [&](const osg::Vec2d& xy) { return osg::Vec4d(xy.x(), xy.y(), p.z(), 1.0) * sceneToClip; };
    auto window = [&](const osg::Vec4d& c)
    { return osg::Vec2d(c.x() / c.w() * pixelsPerNdc.x(), c.y() / c.w() * pixelsPerNdc.y()); };
    const osg::Vec4d cp = osg::Vec4d(p, 1.0) * sceneToClip;
    const osg::Vec2d here = window(cp);
    const double wMin = kNearFraction * cp.w();
    auto clipNear = [&](const osg::Vec4d& a, const osg::Vec4d& b)
    { return a.w() >= wMin ? a : a + (b - a) * ((wMin - a.w()) / (b.w() - a.w())); };
    Nearest best;
    double bestMargin = -std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < segments.size(); ++k)
    {
        const osg::Vec4d ca = clip(segments[k].a), cb = clip(segments[k].b);
        if (ca.w() < wMin && cb.w() < wMin) continue;
        const osg::Vec2d a = window(clipNear(ca, cb)) - here, b = window(clipNear(cb, ca)) - here;
        const osg::Vec2d ab = b - a;
        const double len2 = ab * ab;
        const double t = len2 > 0.0 ? osg::clampBetween(-(a * ab) / len2, 0.0, 1.0) : 0.0;
        const double pixels = (a + ab * t).length();
        const double margin = 0.5 * segments[k].width - pixels;
        if (margin > bestMargin)
        {
            bestMargin = margin;
            best.index = int(k);
            best.pixels = pixels;
        }
    }
    return best;
}

osg::Vec3f RouteLine::shade(const osg::Vec3f& rgb, double pixels, const Segment& segment)
{
    const double half = 0.5 * segment.width;
    const double cover = osg::clampBetween(half + 0.5 - pixels, 0.0, 1.0) * segment.color.a();
    if (!(cover > 0.0)) return rgb;
    const osg::Vec3f fill(segment.color.r(), segment.color.g(), segment.color.b());
    osg::Vec3f line = fill;
    if (segment.width >= 4.0)
    {
        const float f = float(osg::clampBetween(half - 0.5 - pixels, 0.0, 1.0));
        line = fill * (kCasingBrightness * (1.0f - f) + f);
    }
    return rgb * float(1.0 - cover) + line * float(cover);
}

} // namespace osgLoA
