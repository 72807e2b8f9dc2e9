/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/filtering/FilterRegistry>
#include <osgLoA/filtering/L0Smoothing>

#include <cmath>

namespace osgLoA
{

static FilterRegistry::Entry<L0Smoothing>
    s_registeredL0Smoothing("l0", "L0 gradient minimization (Xu et al. 2011; lambda, kappa, beta_max); CPU only");

namespace
{
using Complex = std::complex<double>;
const double kPi = 3.14159265358979323846;

inline Complex mul(const Complex& a, const Complex& b)
{
    return Complex(a.real() * b.real() - a.imag() * b.imag(), a.real() * b.imag() + a.imag() * b.real());
}

/** An unnormalized DFT of one length: radix-2 for powers of two, otherwise Bluestein's algorithm (the DFT as
 *  a convolution with the chirp e^(i pi k^2 / n), done by radix-2 FFTs of a power of two m >= 2n - 1). */
class Fft
{
public:
    explicit Fft(int n) : _n(n)
    {
        _pow2 = n > 0 && (n & (n - 1)) == 0;
        _m = 1;
        while (_m < (_pow2 ? n : 2 * n - 1))
            _m <<= 1;
        int bits = 0;
        while ((1 << bits) < _m)
            ++bits;
        _reverse.resize(std::size_t(_m));
        for (int i = 0; i < _m; ++i)
        {
            int r = 0;
            for (int b = 0; b < bits; ++b)
                if (i & (1 << b)) r |= 1 << (bits - 1 - b);
            _reverse[std::size_t(i)] = r;
        }
        _twiddle.resize(std::size_t(std::max(1, _m / 2)));
        for (int k = 0; k < _m / 2; ++k)
            _twiddle[std::size_t(k)] = std::polar(1.0, -2.0 * kPi * k / _m);
        if (_pow2) return;
        // chirp[k] = e^(-i pi k^2 / n), with k^2 taken mod 2n for accuracy.
        _chirp.resize(std::size_t(n));
        for (int k = 0; k < n; ++k)
        {
            const long long k2 = (static_cast<long long>(k) * k) % (2LL * n);
            _chirp[std::size_t(k)] = std::polar(1.0, -kPi * double(k2) / n);
        }
        _chirpFft.assign(std::size_t(_m), Complex(0, 0));
        _chirpFft[0] = std::conj(_chirp[0]);
        for (int k = 1; k < n; ++k)
            _chirpFft[std::size_t(k)] = _chirpFft[std::size_t(_m - k)] = std::conj(_chirp[std::size_t(k)]);
        radix2(_chirpFft.data(), false);
        _work.resize(std::size_t(_m));
    }

    int size() const { return _n; }

    /** In place, unnormalized, forward (e^-) or inverse (e^+). */
    void transform(Complex* data, bool inverse)
    {
        if (_n <= 1) return;
        if (_pow2)
        {
            radix2(data, inverse);
            return;
        }
        // The inverse is conj(forward(conj(x))).
        for (int k = 0; k < _n; ++k)
        {
            const Complex x = inverse ? std::conj(data[k]) : data[k];
            _work[std::size_t(k)] = mul(x, _chirp[std::size_t(k)]);
        }
        std::fill(_work.begin() + _n, _work.end(), Complex(0, 0));
        radix2(_work.data(), false);
        for (int k = 0; k < _m; ++k)
            _work[std::size_t(k)] = mul(_work[std::size_t(k)], _chirpFft[std::size_t(k)]);
        radix2(_work.data(), true);
        const double scale = 1.0 / _m;
        for (int k = 0; k < _n; ++k)
        {
            const Complex x = mul(_work[std::size_t(k)], _chirp[std::size_t(k)]) * scale;
            data[k] = inverse ? std::conj(x) : x;
        }
    }

private:
    void radix2(Complex* a, bool inverse) const
    {
        for (int i = 0; i < _m; ++i)
        {
            const int r = _reverse[std::size_t(i)];
            if (i < r) std::swap(a[i], a[r]);
        }
        for (int len = 2; len <= _m; len <<= 1)
        {
            const int half = len / 2, step = _m / len;
            for (int i = 0; i < _m; i += len)
                for (int k = 0; k < half; ++k)
                {
                    Complex w = _twiddle[std::size_t(k * step)];
                    if (inverse) w = std::conj(w);
                    const Complex u = a[i + k], v = mul(a[i + k + half], w);
                    a[i + k] = u + v;
                    a[i + k + half] = u - v;
                }
        }
    }

    int _n = 0, _m = 1;
    bool _pow2 = true;
    std::vector<int> _reverse;
    std::vector<Complex> _twiddle, _chirp, _chirpFft, _work;
};

/** 2-D DFT of a W x H row-major array in place (unnormalized). */
void dft2(std::vector<Complex>& data, int W, int H, Fft& rows, Fft& columns, std::vector<Complex>& column,
          bool inverse)
{
    for (int y = 0; y < H; ++y)
        rows.transform(&data[std::size_t(y) * W], inverse);
    column.resize(std::size_t(H));
    for (int x = 0; x < W; ++x)
    {
        for (int y = 0; y < H; ++y)
            column[std::size_t(y)] = data[std::size_t(y) * W + x];
        columns.transform(column.data(), inverse);
        for (int y = 0; y < H; ++y)
            data[std::size_t(y) * W + x] = column[std::size_t(y)];
    }
}
} // namespace

void L0Smoothing::dft(std::vector<std::complex<double>>& data, bool inverse)
{
    Fft f(int(data.size()));
    f.transform(data.data(), inverse);
    if (inverse && !data.empty())
        for (Complex& c : data)
            c /= double(data.size());
}

int L0Smoothing::iterationCount() const
{
    int k = 0;
    for (double beta = 2.0 * double(_lambda); beta < double(_betaMax) && k <= 1000; beta *= double(_kappa))
        ++k;
    return k;
}

FilterImage L0Smoothing::apply(const FilterImage& input, const ImageBorder& border) const
{
    checkParameters();
    if (input.empty()) return input;
    const int w = input.width(), h = input.height();
    // The domain solved on: the image, or its mirrored extension along axes that do not repeat.
    const int W = (border.s != WrapMode::Repeat && w > 1) ? 2 * w : w;
    const int H = (border.t != WrapMode::Repeat && h > 1) ? 2 * h : h;
    const std::size_t n = std::size_t(W) * H;
    std::vector<double> I(3 * n), S(3 * n);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
        {
            const float* p =
                input.texel(wrapIndex(x, w, WrapMode::Mirror), wrapIndex(y, h, WrapMode::Mirror));
            for (int c = 0; c < 3; ++c)
                I[c * n + std::size_t(y) * W + x] = p[c];
        }
    S = I;

    // |F(dx)|^2 + |F(dy)|^2 for the forward differences (periodic).
    std::vector<double> denominator(n);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
            denominator[std::size_t(y) * W + x] =
                4.0 - 2.0 * std::cos(2.0 * kPi * x / W) - 2.0 * std::cos(2.0 * kPi * y / H);

    Fft rows(W), columns(H);
    std::vector<Complex> z1(n), z2(n), column;
    std::vector<double> hv(6 * n);
    const double lambda = _lambda;
    for (double beta = 2.0 * lambda; beta < double(_betaMax); beta *= double(_kappa))
    {
        // (h, v) subproblem: forward differences, zeroed where their squared sum is below lambda/beta.
        const double threshold = lambda / beta;
        for (int y = 0; y < H; ++y)
        {
            const int y1 = y + 1 == H ? 0 : y + 1;
            for (int x = 0; x < W; ++x)
            {
                const int x1 = x + 1 == W ? 0 : x + 1;
                const std::size_t k = std::size_t(y) * W + x;
                double magnitude = 0;
                for (int c = 0; c < 3; ++c)
                {
                    const double* s = &S[c * n];
                    const double dh = s[std::size_t(y) * W + x1] - s[k];
                    const double dv = s[std::size_t(y1) * W + x] - s[k];
                    hv[(2 * c) * n + k] = dh;
                    hv[(2 * c + 1) * n + k] = dv;
                    magnitude += dh * dh + dv * dv;
                }
                if (magnitude < threshold)
                    for (int c = 0; c < 6; ++c)
                        hv[c * n + k] = 0.0;
            }
        }
        // S subproblem: S = K * (I + beta div(h, v)) with K's transform 1 / (1 + beta D); the divergence (the
        // adjoint of the forward differences) is h(x-1) - h(x) + v(y-1) - v(y).
        for (int y = 0; y < H; ++y)
        {
            const int y0 = y == 0 ? H - 1 : y - 1;
            for (int x = 0; x < W; ++x)
            {
                const int x0 = x == 0 ? W - 1 : x - 1;
                const std::size_t k = std::size_t(y) * W + x;
                double u[3];
                for (int c = 0; c < 3; ++c)
                {
                    const double* hc = &hv[(2 * c) * n];
                    const double* vc = &hv[(2 * c + 1) * n];
                    u[c] = I[c * n + k] +
                           beta * (hc[std::size_t(y) * W + x0] - hc[k] + vc[std::size_t(y0) * W + x] - vc[k]);
                }
                z1[k] = Complex(u[0], u[1]);
                z2[k] = Complex(u[2], 0.0);
            }
        }
        // The kernel is real and even, so two real channels share one complex transform.
        dft2(z1, W, H, rows, columns, column, false);
        dft2(z2, W, H, rows, columns, column, false);
        const double scale = 1.0 / double(n);
        for (std::size_t k = 0; k < n; ++k)
        {
            const double f = scale / (1.0 + beta * denominator[k]);
            z1[k] *= f;
            z2[k] *= f;
        }
        dft2(z1, W, H, rows, columns, column, true);
        dft2(z2, W, H, rows, columns, column, true);
        for (std::size_t k = 0; k < n; ++k)
        {
            S[k] = z1[k].real();
            S[n + k] = z1[k].imag();
            S[2 * n + k] = z2[k].real();
        }
    }

    FilterImage out(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
        {
            const std::size_t k = std::size_t(y) * W + x;
            out.set(x, y,
                    osg::Vec4f(float(S[k]), float(S[n + k]), float(S[2 * n + k]), input.texel(x, y)[3]));
        }
    return out;
}

std::vector<FilterParameter> L0Smoothing::parameters()
{
    FilterParameter lambda;
    lambda.name = "lambda";
    lambda.description = "weight of the gradient count (larger: fewer edges kept)";
    lambda.minimum = 1e-6;
    lambda.maximum = 1;
    lambda.get = [this] { return double(_lambda); };
    lambda.set = [this](double v) { _lambda = float(v); };

    FilterParameter kappa;
    kappa.name = "kappa";
    kappa.description = "growth rate of beta per iteration";
    kappa.minimum = 1.1;
    kappa.maximum = 100;
    kappa.get = [this] { return double(_kappa); };
    kappa.set = [this](double v) { _kappa = float(v); };

    FilterParameter betaMax;
    betaMax.name = "beta_max";
    betaMax.description = "beta at which the iteration stops";
    betaMax.minimum = 1;
    betaMax.maximum = 1e8;
    betaMax.get = [this] { return double(_betaMax); };
    betaMax.set = [this](double v) { _betaMax = float(v); };
    return {lambda, kappa, betaMax};
}

} // namespace osgLoA
