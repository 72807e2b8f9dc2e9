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
