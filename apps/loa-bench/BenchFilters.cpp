// loa-bench cases "filters" and "preprocess": the image filters of paper 000 against OpenCV.
//  - filters: each filter on one 512x512 texture: our GPU passes (GpuFilterEngine, glFinish-timed
//    dispatches), our CPU reference, and OpenCV's implementation where it has one; the error
//    columns are our GPU result (our CPU one for CPU-only filters) against OpenCV's, in 8-bit
//    units (mean and max absolute difference over RGB).
//  - preprocess: paper 004 §3.1's pre-process, bilateral then DoG on every mip level of 1,520
//    textures of 128x128 (about 20 minutes in that paper), as textures per second: OpenCV
//    (cv::bilateralFilter then a DoG of cv::GaussianBlur), our GPU passes on atlases of whole
//    pyramids, our CPU references on all cores, and the flow-based version (flow-based
//    bilateral then FDoG) on the GPU.
#include "BenchCase.h"

#include <osgLoA/city/CityTextures>
#include <osgLoA/filtering/FilterRegistry>
#include <osgLoA/filtering/GpuFilterEngine>
#include <osgLoA/render/HeadlessContext>

#include <GL/gl.h>

#ifdef LOA_HAVE_OPENCV
#include <opencv2/imgproc.hpp>
#include <opencv2/ximgproc.hpp>
#endif

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <thread>

namespace
{
/** A filter specification without commas (the CSV's charts split on them): k=v;k=v. */
std::string noCommas(std::string s)
{
    for (char& c : s)
        if (c == ',') c = ';';
    return s;
}

double msSince(std::chrono::steady_clock::time_point t0)
{
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

/** The demo city's texture `index` (facades, then surfaces), tiled over w x h. */
osgLoA::FilterImage demoTexture(std::size_t index, int w, int h, int offsetX = 0, int offsetY = 0)
{
    std::vector<osg::ref_ptr<osg::Image>> images;
    for (const osgLoA::FacadeStyle& f : osgLoA::CityTextures::facadeStyles())
        images.push_back(osgLoA::CityTextures::facade(f));
    for (const char* k : {"roof-gravel", "roof-tiles", "terrain", "park-grass", "forest-floor", "road-minor",
                          "road-major", "water"})
        images.push_back(osgLoA::CityTextures::surface(k));
    const osgLoA::FilterImage src = osgLoA::FilterImage::fromImage(*images[index % images.size()]);
    osgLoA::FilterImage out(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            out.set(x, y, src.get((x + offsetX) % src.width(), (y + offsetY) % src.height()));
    return out;
}

/** A context made current with an engine, for one case. */
struct Gpu
{
    osg::ref_ptr<osgLoA::HeadlessContext> context = new osgLoA::HeadlessContext;
    osg::ref_ptr<osgLoA::GpuFilterEngine> engine;
    Gpu()
    {
        if (!context->realize() || !context->makeCurrent()) throw std::runtime_error("no OpenGL context");
        engine = new osgLoA::GpuFilterEngine(*context->getState());
    }
    ~Gpu()
    {
        engine->releaseGLObjects();
        context->releaseContext();
    }
};

/** Runs fn `frames` times after one warm-up run; the times in ms. */
osgLoA::FrameTimes timed(unsigned frames, const std::function<void()>& fn)
{
    osgLoA::FrameTimes t;
    fn();
    for (unsigned i = 0; i < frames; ++i)
    {
        const auto t0 = std::chrono::steady_clock::now();
        fn();
        t.milliseconds.push_back(msSince(t0));
    }
    return t;
}

/** One untimed-warm-up-free run (for runs of many seconds). */
osgLoA::FrameTimes once(const std::function<void()>& fn)
{
    osgLoA::FrameTimes t;
    const auto t0 = std::chrono::steady_clock::now();
    fn();
    t.milliseconds.push_back(msSince(t0));
    return t;
}

std::string fixed(double v, int digits = 3)
{
    std::ostringstream s;
    s << std::fixed << std::setprecision(digits) << v;
    return s.str();
}

#ifdef LOA_HAVE_OPENCV
cv::Mat toMat(const osgLoA::FilterImage& img)
{
    cv::Mat m(img.height(), img.width(), CV_8UC3);
    for (int y = 0; y < img.height(); ++y)
        for (int x = 0; x < img.width(); ++x)
        {
            const float* p = img.texel(x, y);
            cv::Vec3b& q = m.at<cv::Vec3b>(y, x);
            for (int c = 0; c < 3; ++c)
                q[c] = cv::saturate_cast<unsigned char>(std::lround(p[c] * 255.0f));
        }
    return m;
}

/** Mean and max absolute difference over RGB, in 8-bit units. */
std::pair<double, double> difference8(const osgLoA::FilterImage& a, const cv::Mat& b)
{
    double sum = 0, mx = 0;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x)
        {
            const float* p = a.texel(x, y);
            const cv::Vec3b q = b.at<cv::Vec3b>(y, x);
            for (int c = 0; c < 3; ++c)
            {
                const double d = std::fabs(std::round(double(p[c]) * 255.0) - q[c]);
                sum += d;
                mx = std::max(mx, d);
            }
        }
    return {sum / (double(a.texelCount()) * 3.0), mx};
}
#endif

/** A filter from the registry, or null with a message when it is not there. */
osg::ref_ptr<osgLoA::ImageFilter> tryCreate(const std::string& spec)
{
    try
    {
        return osgLoA::FilterRegistry::create(spec);
    }
    catch (const std::exception& e)
    {
        std::cerr << "  skipped '" << spec << "': " << e.what() << "\n";
        return nullptr;
    }
}
} // namespace

std::vector<Row> filters(unsigned frames, std::string& renderer)
{
    std::vector<Row> rows;
    Gpu gpu;
    renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    const osgLoA::FilterImage image = demoTexture(0, 512, 512);
    const osgLoA::ImageBorder border(osgLoA::WrapMode::Mirror, osgLoA::WrapMode::Mirror);
    struct Case
    {
        std::string spec;
#ifdef LOA_HAVE_OPENCV
        std::function<void(const cv::Mat&, cv::Mat&)> opencv;
#endif
    };
    // OpenCV parameters mapped from ours: colours in [0, 1] are 0..255 there; BORDER_REFLECT is
    // our mirror mode (GL_MIRRORED_REPEAT repeats the edge texel).
    std::vector<Case> cases = {
        {"gaussian:sigma=2",
#ifdef LOA_HAVE_OPENCV
         [](const cv::Mat& s, cv::Mat& d)
         { cv::GaussianBlur(s, d, cv::Size(13, 13), 2.0, 2.0, cv::BORDER_REFLECT); }
#endif
        },
        {"bilateral:sigma_d=3,sigma_r=0.1,range_norm=l1",
#ifdef LOA_HAVE_OPENCV
         [](const cv::Mat& s, cv::Mat& d) { cv::bilateralFilter(s, d, 13, 25.5, 3.0, cv::BORDER_REFLECT); }
#endif
        },
        {"guided:radius=4,eps=0.01",
#ifdef LOA_HAVE_OPENCV
         [](const cv::Mat& s, cv::Mat& d) { cv::ximgproc::guidedFilter(s, s, d, 4, 0.01 * 255 * 255); }
#endif
        },
        {"domain_transform:sigma_s=20,sigma_r=0.2",
#ifdef LOA_HAVE_OPENCV
         [](const cv::Mat& s, cv::Mat& d)
         { cv::ximgproc::dtFilter(s, s, d, 20, 0.2 * 255, cv::ximgproc::DTF_RF, 3); }
#endif
        },
        {"l0:lambda=0.02,kappa=2",
#ifdef LOA_HAVE_OPENCV
         [](const cv::Mat& s, cv::Mat& d) { cv::ximgproc::l0Smooth(s, d, 0.02, 2.0); }
#endif
        },
        {"dog",
#ifdef LOA_HAVE_OPENCV
         nullptr
#endif
        },
        {"flow_bilateral",
#ifdef LOA_HAVE_OPENCV
         nullptr
#endif
        },
        {"kuwahara",
#ifdef LOA_HAVE_OPENCV
         nullptr
#endif
        },
        {"akf",
#ifdef LOA_HAVE_OPENCV
         nullptr
#endif
        },
        {"shock",
#ifdef LOA_HAVE_OPENCV
         nullptr
#endif
        },
        {"quantize",
#ifdef LOA_HAVE_OPENCV
         nullptr
#endif
        }};
    for (const Case& c : cases)
    {
        osg::ref_ptr<osgLoA::ImageFilter> f = tryCreate(c.spec);
        if (!f) continue;
        const std::string spec = noCommas(f->getParameterString());
        const std::string name = f->filterName();
        osgLoA::FilterImage ours;
        if (f->hasGpuImplementation())
        {
            osgLoA::GpuFilterEngine& e = *gpu.engine;
            osgLoA::GpuFilterEngine::Region r;
            r.width = image.width();
            r.height = image.height();
            r.border = border;
            const unsigned src = e.createAtlas(r.width, r.height), dst = e.createAtlas(r.width, r.height);
            e.upload(src, r, image);
            Row row;
            row.parameters = name + " impl=gpu spec=" + spec + " size=512x512";
            row.times = timed(frames,
                              [&]
                              {
                                  e.run(*f, src, dst, {r});
                                  glFinish();
                              });
            ours = e.download(dst, r);
            e.destroyAtlas(src);
            e.destroyAtlas(dst);
            rows.push_back(row);
            std::cerr << "  " << row.parameters << ": median " << row.times.median() << " ms\n";
        }
        {
            Row row;
            row.parameters = name + " impl=cpu spec=" + spec + " size=512x512";
            osgLoA::FilterImage cpu;
            row.times = timed(std::max(1u, frames / 5), [&] { cpu = f->apply(image, border); });
            if (ours.empty()) ours = cpu;
            rows.push_back(row);
            std::cerr << "  " << row.parameters << ": median " << row.times.median() << " ms\n";
        }
#ifdef LOA_HAVE_OPENCV
        if (c.opencv)
        {
            const cv::Mat in = toMat(image);
            cv::Mat out;
            Row row;
            row.parameters = name + " impl=opencv spec=" + spec + " size=512x512";
            row.times = timed(frames, [&] { c.opencv(in, out); });
            const auto d = difference8(ours, out);
            row.errorMean = fixed(d.first, 4);
            row.errorMax = fixed(d.second, 1);
            rows.push_back(row);
            std::cerr << "  " << row.parameters << ": median " << row.times.median()
                      << " ms, ours vs opencv mean " << row.errorMean << " max " << row.errorMax
                      << " (8-bit)\n";
        }
#endif
    }
    return rows;
}

namespace
{
constexpr int kTextures = 1520, kSize = 128;
/** Each texture's pyramid in a 192x128 cell: level 0 at (0, 0), level k > 0 at
 *  (128, 128 - 128/2^(k-1)) (the classic mip layout); 10 x 16 cells in a 1920x2048 atlas. */
constexpr int kCellW = 192, kCellH = 128, kCellsX = 10, kCellsY = 16, kPerAtlas = kCellsX * kCellsY;

std::vector<osgLoA::GpuFilterEngine::Region> cellRegions(int cell)
{
    std::vector<osgLoA::GpuFilterEngine::Region> regions;
    const int cx = (cell % kCellsX) * kCellW, cy = (cell / kCellsX) * kCellH;
    int size = kSize, y = 0;
    for (int level = 0; size >= 1; ++level, size /= 2)
    {
        osgLoA::GpuFilterEngine::Region r;
        r.width = r.height = size;
        r.x = cx + (level == 0 ? 0 : kSize);
        r.y = cy + (level == 0 ? 0 : y);
        if (level > 0) y += size;
        r.border = osgLoA::ImageBorder(osgLoA::WrapMode::Repeat, osgLoA::WrapMode::Repeat);
        regions.push_back(r);
    }
    return regions;
}

std::vector<std::vector<osgLoA::FilterImage>> preprocessInputs()
{
    std::vector<std::vector<osgLoA::FilterImage>> pyramids;
    for (int i = 0; i < kTextures; ++i)
        pyramids.push_back(
            demoTexture(std::size_t(i), kSize, kSize, (i * 37) % 97, (i * 53) % 89).mipPyramid());
    return pyramids;
}
} // namespace

std::vector<Row> preprocess(unsigned frames, std::string& renderer)
{
    std::vector<Row> rows;
    const auto pyramids = preprocessInputs();
    std::size_t texels = 0;
    for (const auto& p : pyramids)
        for (const auto& l : p)
            texels += l.texelCount();
    std::cerr << "  " << kTextures << " textures of " << kSize << "x" << kSize << ", " << pyramids[0].size()
              << " levels each, " << texels << " texels\n";
    const unsigned runs = std::max(1u, std::min(frames, 3u));
    auto addRow = [&](const std::string& what, const osgLoA::FrameTimes& t)
    {
        Row row;
        std::ostringstream p;
        p << what << " textures=" << kTextures << " size=" << kSize << " levels=" << pyramids[0].size()
          << " textures_per_s=" << fixed(kTextures / (t.median() / 1000.0), 1);
        row.parameters = p.str();
        row.times = t;
        rows.push_back(row);
        std::cerr << "  " << row.parameters << ": median " << t.median() << " ms\n";
    };

    // The plain pre-process: bilateral, then DoG (paper 004 §3.1).
    const std::string plainSpec = "bilateral:sigma_d=2,sigma_r=0.1,range_norm=l1+dog:sigma_e=1,flow=0";
    const std::string flowSpec = "flow_bilateral+dog:sigma_e=1,flow=1";
#ifdef LOA_HAVE_OPENCV
    {
        std::vector<std::vector<cv::Mat>> mats;
        for (const auto& p : pyramids)
        {
            mats.emplace_back();
            for (const auto& l : p)
                mats.back().push_back(toMat(l));
        }
        osgLoA::FrameTimes t =
            timed(runs - 1,
                  [&]
                  {
                      cv::Mat b, g, g1, g2;
                      for (const auto& p : mats)
                          for (const cv::Mat& m : p)
                          {
                              cv::bilateralFilter(m, b, 9, 25.5, 2.0, cv::BORDER_REFLECT);
                              cv::cvtColor(b, g, cv::COLOR_BGR2GRAY);
                              cv::GaussianBlur(g, g1, cv::Size(7, 7), 1.0, 1.0, cv::BORDER_REFLECT);
                              cv::GaussianBlur(g, g2, cv::Size(11, 11), 1.6, 1.6, cv::BORDER_REFLECT);
                              cv::subtract(g1, g2, g, cv::noArray(), CV_16S);
                          }
                  });
        addRow("opencv plain filter=bilateral+dog", t);
    }
#endif
    Gpu gpu;
    renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    for (const std::string& spec : {plainSpec, flowSpec})
    {
        osg::ref_ptr<osgLoA::ImageFilter> f = tryCreate(spec);
        if (!f || !f->hasGpuImplementation()) continue;
        osgLoA::GpuFilterEngine& e = *gpu.engine;
        const unsigned src = e.createAtlas(kCellW * kCellsX, kCellH * kCellsY);
        const unsigned dst = e.createAtlas(kCellW * kCellsX, kCellH * kCellsY);
        osgLoA::FrameTimes t =
            timed(runs - 1,
                  [&]
                  {
                      // Upload a batch of pyramids, filter every level of them in one run, read them back.
                      for (int first = 0; first < kTextures; first += kPerAtlas)
                      {
                          std::vector<osgLoA::GpuFilterEngine::Region> regions;
                          for (int i = first; i < std::min(kTextures, first + kPerAtlas); ++i)
                          {
                              const auto cell = cellRegions(i - first);
                              for (std::size_t l = 0; l < cell.size(); ++l)
                                  e.upload(src, cell[l], pyramids[std::size_t(i)][l]);
                              regions.insert(regions.end(), cell.begin(), cell.end());
                          }
                          e.run(*f, src, dst, regions);
                          // One read-back of the whole atlas per batch (the levels are cut from it on the
                          // CPU): a read-back per level would stall the pipeline 1,280 times.
                          osgLoA::GpuFilterEngine::Region all;
                          all.width = kCellW * kCellsX;
                          all.height = kCellH * kCellsY;
                          const osgLoA::FilterImage atlas = e.download(dst, all);
                          for (const auto& r : regions)
                          {
                              osgLoA::FilterImage level(r.width, r.height);
                              for (int y = 0; y < r.height; ++y)
                                  std::copy(atlas.texel(r.x, r.y + y),
                                            atlas.texel(r.x, r.y + y) + 4 * r.width, level.texel(0, y));
                          }
                      }
                      glFinish();
                  });
        e.destroyAtlas(src);
        e.destroyAtlas(dst);
        addRow(std::string("gpu ") + (spec == plainSpec ? "plain" : "flow-based") +
                   " filter=" + noCommas(spec),
               t);
    }
    {
        osg::ref_ptr<osgLoA::ImageFilter> f = tryCreate(plainSpec);
        if (f)
        {
            const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
            osgLoA::FrameTimes t = once(
                [&]
                {
                    std::vector<std::thread> pool;
                    for (unsigned k = 0; k < threads; ++k)
                        pool.emplace_back(
                            [&, k]
                            {
                                for (std::size_t i = k; i < pyramids.size(); i += threads)
                                    for (const auto& l : pyramids[i])
                                        (void)f->apply(l, osgLoA::ImageBorder(osgLoA::WrapMode::Repeat,
                                                                              osgLoA::WrapMode::Repeat));
                            });
                    for (auto& th : pool)
                        th.join();
                });
            addRow("cpu plain threads=" + std::to_string(threads) + " filter=" + noCommas(plainSpec), t);
        }
    }
    return rows;
}
