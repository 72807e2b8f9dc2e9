/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/util/SpectralResidualSaliency>

#include <algorithm>
#include <cmath>
#include <complex>
#include <stdexcept>

namespace osgLoA
{

namespace
{
typedef std::complex<double> Complex;
constexpr int N = SpectralResidualSaliency::kSize;

/** In-place radix-2 FFT of n values at stride `stride` (inverse: conjugate twiddles, no scaling). */
void fft(Complex* a, int n, int stride, bool inverse)
{
    for (int i = 1, j = 0; i < n; ++i)
    {
        int bit = n >> 1;
        for (; j & bit; bit >>= 1)
            j ^= bit;
        j ^= bit;
        if (i < j) std::swap(a[i * stride], a[j * stride]);
    }
    for (int len = 2; len <= n; len <<= 1)
    {
        const double angle = 2.0 * M_PI / len * (inverse ? 1.0 : -1.0);
        const Complex w(std::cos(angle), std::sin(angle));
        for (int i = 0; i < n; i += len)
        {
            Complex wk(1.0, 0.0);
            for (int k = 0; k < len / 2; ++k)
            {
                Complex& u = a[(i + k) * stride];
                Complex& v = a[(i + k + len / 2) * stride];
                const Complex t = v * wk;
                v = u - t;
                u = u + t;
                wk *= w;
            }
        }
    }
}

/** The image pixels [x0, x1) x [y0, y1) of map cell (cx, cy) of an image w x h (at least one). */
struct CellRange
{
    int x0, x1, y0, y1;
    CellRange(int cx, int cy, int w, int h)
        : x0(cx * w / N), x1(std::max(x0 + 1, (cx + 1) * w / N)), y0(cy * h / N),
          y1(std::max(y0 + 1, (cy + 1) * h / N))
    {
    }
    int pixels() const { return (x1 - x0) * (y1 - y0); }
};

void fft2(std::vector<Complex>& a, bool inverse)
{
    for (int y = 0; y < N; ++y)
        fft(&a[std::size_t(y) * N], N, 1, inverse);
    for (int x = 0; x < N; ++x)
        fft(&a[std::size_t(x)], N, N, inverse);
}
} // namespace

std::vector<float> SpectralResidualSaliency::compute(const osg::Image& image)
{
    const int w = image.s(), h = image.t();
    const GLenum f = image.getPixelFormat();
    if (w <= 0 || h <= 0 || !image.data() || image.getDataType() != GL_UNSIGNED_BYTE ||
        (f != GL_RGB && f != GL_RGBA))
        throw std::invalid_argument("saliency: the image is not 8-bit RGB or RGBA");
    const int channels = f == GL_RGBA ? 4 : 3;
    // Luminance averaged over each cell's pixels (area resampling to N x N).
    std::vector<Complex> a(std::size_t(N) * N);
    for (int cy = 0; cy < N; ++cy)
        for (int cx = 0; cx < N; ++cx)
        {
            const CellRange c(cx, cy, w, h);
            double sum = 0.0;
            for (int y = c.y0; y < c.y1; ++y)
            {
                const unsigned char* row = image.data(0, y);
                for (int x = c.x0; x < c.x1; ++x)
                {
                    const unsigned char* p = row + std::size_t(x) * channels;
                    sum += (0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2]) / 255.0;
                }
            }
            a[std::size_t(cy) * N + cx] = sum / double(c.pixels());
        }
    fft2(a, false);
    // The spectral residual: log amplitude less its 3 x 3 mean (edges replicated), the phase kept.
    std::vector<double> logA(a.size()), phase(a.size());
    for (std::size_t i = 0; i < a.size(); ++i)
    {
        logA[i] = std::log(std::max(std::abs(a[i]), 1e-12));
        phase[i] = std::arg(a[i]);
    }
    for (int y = 0; y < N; ++y)
        for (int x = 0; x < N; ++x)
        {
            double mean = 0.0;
            for (int j = -1; j <= 1; ++j)
                for (int i = -1; i <= 1; ++i)
                    mean += logA[std::size_t(std::clamp(y + j, 0, N - 1)) * N +
                                 std::size_t(std::clamp(x + i, 0, N - 1))];
            const std::size_t k = std::size_t(y) * N + std::size_t(x);
            a[k] = std::polar(std::exp(logA[k] - mean / 9.0), phase[k]);
        }
    fft2(a, true);
    std::vector<double> s(a.size());
    for (std::size_t i = 0; i < a.size(); ++i)
        s[i] = std::norm(a[i]);
    // Gaussian blur, 5 taps, sigma 8, separable, edges reflected (as OpenCV's default border).
    double kernel[5], ksum = 0.0;
    for (int i = -2; i <= 2; ++i)
        ksum += kernel[i + 2] = std::exp(-double(i * i) / (2.0 * 64.0));
    auto reflect = [](int i) { return i < 0 ? -i : (i >= N ? 2 * N - 2 - i : i); };
    std::vector<double> tmp(s.size());
    for (int y = 0; y < N; ++y)
        for (int x = 0; x < N; ++x)
        {
            double v = 0.0;
            for (int i = -2; i <= 2; ++i)
                v += kernel[i + 2] * s[std::size_t(y) * N + std::size_t(reflect(x + i))];
            tmp[std::size_t(y) * N + std::size_t(x)] = v / ksum;
        }
    for (int y = 0; y < N; ++y)
        for (int x = 0; x < N; ++x)
        {
            double v = 0.0;
            for (int j = -2; j <= 2; ++j)
                v += kernel[j + 2] * tmp[std::size_t(reflect(y + j)) * N + std::size_t(x)];
            s[std::size_t(y) * N + std::size_t(x)] = v / ksum;
        }
    const auto [lo, hi] = std::minmax_element(s.begin(), s.end());
    const double range = *hi - *lo;
    std::vector<float> map(s.size(), 0.0f);
    if (range > 0.0)
        for (std::size_t i = 0; i < s.size(); ++i)
            map[i] = float((s[i] - *lo) / range);
    return map;
}

double SpectralResidualSaliency::massInside(const std::vector<float>& map,
                                            const std::vector<unsigned char>& mask, int width, int height)
{
    if (width <= 0 || height <= 0 || mask.size() != std::size_t(width) * std::size_t(height))
        throw std::invalid_argument("saliency: the mask is not the image's size");
    if (map.size() != std::size_t(N) * N) throw std::invalid_argument("saliency: the map is not 64 x 64");
    double inside = 0.0, total = 0.0;
    for (int cy = 0; cy < N; ++cy)
        for (int cx = 0; cx < N; ++cx)
        {
            const CellRange c(cx, cy, width, height);
            long in = 0;
            for (int y = c.y0; y < c.y1; ++y)
                for (int x = c.x0; x < c.x1; ++x)
                    in += mask[std::size_t(y) * std::size_t(width) + std::size_t(x)] ? 1 : 0;
            const double m = map[std::size_t(cy) * N + std::size_t(cx)];
            inside += m * double(in) / double(c.pixels());
            total += m;
        }
    return total > 0.0 ? inside / total : 0.0;
}

} // namespace osgLoA
