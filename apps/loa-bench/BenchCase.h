// loa-bench: what a benchmark case returns. Each case lives in its own file when it is more
// than a few lines (Bench<Case>.cpp) and is listed in the cases table of loa-bench.cpp.
#pragma once

#include <osgLoA/render/OffscreenRenderer>

#include <osg/Group>

#include <string>
#include <vector>

/** One CSV row: the case's parameters, the timed repetitions and its accuracy measure. */
struct Row
{
    std::string parameters;
    osgLoA::FrameTimes times;
    std::string errorMean, errorMax;
    /** The check of the row's last frame failed (its reason is in the parameters): loa-bench
     *  writes the row, then exits 1 naming it. A row whose frame is wrong is a bug, not a number. */
    bool frameFailed = false;
};

/** Checks a benchmark's last frame against a reference frame of the same view (plain rendering).
 *  Covered pixels are those not of the clear colour (more than 1/255 off in a channel). At most
 *  0.2 % of the frame may be covered in the reference with no covered pixel within one pixel in
 *  the frame (content missing), as many the other way round (drawn over the background), and as
 *  many black (< 4/255) where the reference is not dark (< 32/255). Returns "" when the frame
 *  passes, else what is wrong. */
std::string checkFrame(const osg::Image& frame, const osg::Image& reference, const osg::Vec4& clearColor);

/** The check for frames whose colours a style changes on purpose (abstraction, filtering,
 *  palettes): no 16x16 block entirely black where the reference (plain rendering of the same
 *  view) has content, and not one colour over the whole frame. Returns "" when it passes. */
std::string checkBlocks(const osg::Image& frame, const osg::Image& reference);

/** The mean per-pixel change between two frames of one size (8-bit units, over RGB): the
 *  temporal-coherence measure of the abstraction and cartographic cases. */
double meanChange(const osg::Image& a, const osg::Image& b);

/** The mean change between consecutive frames of a camera move: `frames` frames, the renderer's
 *  current view turned 0.25 degrees further about its look-at centre (Z up) each frame; the view is
 *  restored afterwards. */
double temporalChange(osgLoA::OffscreenRenderer& r, unsigned frames);

/** Writes a benchmark's frame to out/bench-frames/NAME.png, to be looked at. */
void keepFrame(const osg::Image& frame, const std::string& name);

/** The demo city (default CityParameters), generated once per process. */
osg::ref_ptr<osg::Node> demoCity();
/** The demo city and, when found (run from the repository root after scripts/fetch-test-data),
 *  data/test-scenes/opencity-block.osgt classified by the default rules, named "demo-city" and
 *  "opencity-block". */
std::vector<std::pair<std::string, osg::ref_ptr<osg::Node>>> demoCityAndOpenCityBlock();

/** An offscreen renderer of `scene` at w x h with `samples` MSAA samples, from a named camera
 *  of the demo city (docs/demo-city.md). */
osg::ref_ptr<osgLoA::OffscreenRenderer> makeRenderer(int w, int h, int samples, osg::Node* scene,
                                                     const std::string& camera = "oblique");

/** `scene` under a group with the project's loa_plain program (textured, lit): plain rendering. */
osg::ref_ptr<osg::Group> withPlainProgram(osg::Node* scene);

/** A case: runs with `frames` timed repetitions per configuration, sets `renderer` to the GL
 *  renderer string when it used GL (left empty: "none (CPU only)"). */
using BenchCaseFn = std::vector<Row> (*)(unsigned frames, std::string& renderer);

/** Case "interest" (BenchInterest.cpp): ScenarioEvaluator::evaluate per frame for synthetic
 *  cities of 1k, 10k and 100k features and the distance, route and view-angle scenarios. */
std::vector<Row> interest(unsigned frames, std::string& renderer);
/** classify-objects: one real object, one feature (FeatureClassifier step 5) on the real test
 *  scenes, per grouping variant: classify time against the relative error of the per-type
 *  feature counts to the hand counts (data/test-scenes/NAME.counts.json). BenchClassifyObjects.cpp. */
std::vector<Row> classifyObjects(unsigned frames, std::string& renderer);

/** Case "distance-field" (BenchDistanceField.cpp): the region-interest distance map at 512^2,
 *  1024^2 and 2048^2: CPU seeds, CPU exact EDT, GPU JFA, 1+JFA and JFA+2 against the exact EDT. */
std::vector<Row> distanceField(unsigned frames, std::string& renderer);

/** Case "abuffer" (BenchABuffer.cpp): the stencil-routed A-buffer at 640x480 on K = 1..12
 *  transparent full-view quads, N = 1, 2, 4 (8 where GL_MAX_SAMPLES allows) samples and at most
 *  1..4 routing passes: frame time against the error to the CPU reference of all K fragments. */
std::vector<Row> abuffer(unsigned frames, std::string& renderer);

/** Case "transitions" (BenchTransitions.cpp): paper 004's Table 1 on the demo city at 800x600,
 *  1280x720 and 1920x1080: plain rendering, homogeneous styles through the LoA pipeline and
 *  every library scenario from the oblique camera; plain, homogeneous and view distance from
 *  the street camera; the real test scenes at 1280x720 and 1920x1080 from the street, oblique
 *  and top cameras. Scenarios with fused styles and without (A-buffer only). */
std::vector<Row> transitions(unsigned frames, std::string& renderer);

/** Case "cartographic" (BenchCartographic.cpp): waterlining and relief against flat cartographic
 *  (the ratio of medians in the same run) on the demo city and opencity-block, 1280x720 and
 *  1920x1080, oblique and top cameras. */
std::vector<Row> cartographic(unsigned frames, std::string& renderer);

/** Case "saliency" (BenchSaliency.cpp): paper 004 Figure 10 as a number: the share of a
 *  spectral-residual saliency map's mass inside each library scenario's region of interest,
 *  photorealistic against the scenario, on the demo city and opencity-block. */
std::vector<Row> saliency(unsigned frames, std::string& renderer);

/** Case "filters" (BenchFilters.cpp): each image filter on a 512x512 texture: our GPU passes, our
 *  CPU reference and OpenCV's implementation where it has one (built with OpenCV only). */
std::vector<Row> filters(unsigned frames, std::string& renderer);

/** Case "preprocess" (BenchFilters.cpp): paper 004 §3.1's pre-process (bilateral then DoG on every
 *  mip level of 1,520 textures of 128x128) as textures per second: OpenCV, our GPU passes, our CPU
 *  references on all cores, and the flow-based version on the GPU. */
std::vector<Row> preprocess(unsigned frames, std::string& renderer);

/** Case "filtering" (BenchFiltering.cpp): paper 000's Table 1 on the demo city along a fixed
 *  fly-through at 800x600, 1280x720 and 1920x1080: setups 1-3 of deferred texturing and setup 4
 *  (post-process filtering) with the anisotropic Kuwahara filter, caches cleared per run. */
std::vector<Row> filtering(unsigned frames, std::string& renderer);

/** Case "abstraction" (BenchAbstraction.cpp): Table 1 of papers 001 and 002 on the demo city at
 *  640x480, 800x600 and 1280x1024: regular rendering and every abstraction style along a short
 *  camera move, as ratios to regular rendering; error = frame-to-frame change (coherence). */
std::vector<Row> abstraction(unsigned frames, std::string& renderer);

/** Case "palette" (BenchPalette.cpp): paper 003's offline stages on real photographs: clustering
 *  time against table size (Ward, centroid) and quantization error against the number of colours
 *  (hierarchical against k-means). */
std::vector<Row> palette(unsigned frames, std::string& renderer);

/** Case "viewer" (BenchViewer.cpp): loa-viewer's edit-to-frame latency against scene size: the
 *  circle-of-interest scenario on demo cities of 2x2 to 16x16 blocks and the real test scenes at
 *  1280x720, a fade edit, a region move, a style change and a feature's type change through
 *  ScenarioEditor, each followed by one finished frame, against the same fade edit with a full
 *  re-bind (ratio_to_rebind). */
std::vector<Row> viewer(unsigned frames, std::string& renderer);
