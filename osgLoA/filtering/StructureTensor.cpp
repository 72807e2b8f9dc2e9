/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence.
 */
#include <osgLoA/filtering/GaussianFilter>
#include <osgLoA/filtering/StructureTensor>

#include <cmath>

namespace osgLoA
{

FilterImage StructureTensor::tensor(const FilterImage& input, const ImageBorder& border)
{
    FilterImage out(input.width(), input.height());
    for (int y = 0; y < input.height(); ++y)
        for (int x = 0; x < input.width(); ++x)
        {
            osg::Vec4f n[3][3];
            for (int j = -1; j <= 1; ++j)
                for (int i = -1; i <= 1; ++i)
                    n[j + 1][i + 1] = input.fetch(x + i, y + j, border);
            const osg::Vec4f fx =
                ((n[0][2] + n[1][2] * 2.0f + n[2][2]) - (n[0][0] + n[1][0] * 2.0f + n[2][0])) * 0.125f;
            const osg::Vec4f fy =
                ((n[2][0] + n[2][1] * 2.0f + n[2][2]) - (n[0][0] + n[0][1] * 2.0f + n[0][2])) * 0.125f;
            float E = 0, F = 0, G = 0;
            for (int c = 0; c < 3; ++c)
            {
                E += fx[c] * fx[c];
                F += fx[c] * fy[c];
                G += fy[c] * fy[c];
            }
            out.set(x, y, osg::Vec4f(E, F, G, 0.0f));
        }
    return out;
}

FilterImage StructureTensor::smoothedTensor(const FilterImage& input, float rho, const ImageBorder& border)
{
    FilterImage t = tensor(input, border);
    if (rho <= 0.0f) return t;
    const std::vector<float> w = GaussianFilter::weightsFor(rho);
    return GaussianFilter::blurAxis(GaussianFilter::blurAxis(t, w, 0, border), w, 1, border);
}

osg::Vec4f StructureTensor::flowOf(float E, float F, float G)
{
    const float root = std::sqrt((E - G) * (E - G) + 4.0f * F * F);
    const float l1 = 0.5f * (E + G + root), l2 = 0.5f * (E + G - root);
    if (!(root > 1e-9f * (l1 + l2)) || !(l1 + l2 > 0.0f)) return osg::Vec4f(0.0f, 1.0f, 0.0f, 0.0f);
    float gx, gy;
    if (E >= G)
    {
        gx = l1 - G;
        gy = F;
    }
    else
    {
        gx = F;
        gy = l1 - E;
    }
    const float len = std::sqrt(gx * gx + gy * gy);
    gx /= len;
    gy /= len;
    float tx = -gy, ty = gx;
    if (ty < 0.0f || (ty == 0.0f && tx < 0.0f))
    {
        tx = -tx;
        ty = -ty;
    }
    const float A = root / (l1 + l2);
    // g = (t.y, -t.x): g.x >= 0, so phi is in [-pi/2, pi/2].
    const float phi = std::atan2(-tx, ty);
    return osg::Vec4f(tx, ty, A, phi);
}

osg::Vec2f StructureTensor::tangentOf(float E, float F, float G)
{
    const osg::Vec4f f = flowOf(E, F, G);
    return osg::Vec2f(f[0], f[1]);
}

FilterImage StructureTensor::flow(const FilterImage& tensorImage)
{
    FilterImage out(tensorImage.width(), tensorImage.height());
    for (int y = 0; y < tensorImage.height(); ++y)
        for (int x = 0; x < tensorImage.width(); ++x)
        {
            const float* p = tensorImage.texel(x, y);
            out.set(x, y, flowOf(p[0], p[1], p[2]));
        }
    return out;
}

FilterImage StructureTensor::flow(const FilterImage& input, float rho, const ImageBorder& border)
{
    return flow(smoothedTensor(input, rho, border));
}

std::vector<GpuFilterPass> StructureTensor::tensorPasses(float rho, int input, int firstIndex)
{
    std::vector<GpuFilterPass> passes;
    GpuFilterPass sobel;
    sobel.shader = "loa_filter_tensor.comp.glsl";
    sobel.defines = {{"LOA_TENSOR_STAGE", "0"}};
    sobel.inputs = {input};
    sobel.radius = 1;
    passes.push_back(sobel);
    if (rho > 0.0f)
    {
        const std::vector<float> w = GaussianFilter::weightsFor(rho);
        const int r = int(w.size()) - 1;
        for (int axis = 0; axis < 2; ++axis)
        {
            GpuFilterPass p;
            p.shader = "loa_filter_gaussian.comp.glsl";
            p.defines = {{"LOA_AXIS", std::to_string(axis)}, {"LOA_RADIUS", std::to_string(r)}};
            p.uniforms = {GpuUniform::array("loa_weights", w)};
            p.inputs = {firstIndex + int(passes.size()) - 1};
            p.radius = r;
            passes.push_back(p);
        }
    }
    return passes;
}

std::vector<GpuFilterPass> StructureTensor::flowPasses(float rho, int input, int firstIndex)
{
    std::vector<GpuFilterPass> passes = tensorPasses(rho, input, firstIndex);
    GpuFilterPass f;
    f.shader = "loa_filter_tensor.comp.glsl";
    f.defines = {{"LOA_TENSOR_STAGE", "1"}};
    f.inputs = {firstIndex + int(passes.size()) - 1};
    f.radius = 0;
    passes.push_back(f);
    return passes;
}

} // namespace osgLoA
