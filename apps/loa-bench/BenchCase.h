// loa-bench: what a benchmark case returns. Each case lives in its own file when it is more
// than a few lines (Bench<Case>.cpp) and is listed in the cases table of loa-bench.cpp.
#pragma once

#include <osgLoA/render/OffscreenRenderer>

#include <string>
#include <vector>

/** One CSV row: the case's parameters, the timed repetitions and its accuracy measure. */
struct Row
{
    std::string parameters;
    osgLoA::FrameTimes times;
    std::string errorMean, errorMax;
};

/** A case: runs with `frames` timed repetitions per configuration, sets `renderer` to the GL
 *  renderer string when it used GL (left empty: "none (CPU only)"). */
using BenchCaseFn = std::vector<Row> (*)(unsigned frames, std::string& renderer);

/** Case "interest" (BenchInterest.cpp): ScenarioEvaluator::evaluate per frame for synthetic
 *  cities of 1k, 10k and 100k features and the distance, route and view-angle scenarios. */
std::vector<Row> interest(unsigned frames, std::string& renderer);

/** Case "distance-field" (BenchDistanceField.cpp): the region-interest distance map at 512^2,
 *  1024^2 and 2048^2: CPU seeds, CPU exact EDT, GPU JFA, 1+JFA and JFA+2 against the exact EDT. */
std::vector<Row> distanceField(unsigned frames, std::string& renderer);
