// loa-scenario --image: the interest debug view of paper 004 Figure 5 (black = interest 1, high
// detail; white = interest 0, low detail), rendered headless to a PNG file.
#ifndef OSGLOA_APPS_LOASCENARIO_INTERESTIMAGE_H
#define OSGLOA_APPS_LOASCENARIO_INTERESTIMAGE_H 1

#include "../common/AppSupport.h"

#include <osgLoA/transitions/LoANode>

#include <string>

/** Renders node (a LoANode whose scenario is bound) from camera at width x height as the
 *  interest debug view and writes it to path (.png, atomically). Throws std::runtime_error on
 *  failure (osgLoA::HeadlessContextError when no GL context is available). */
void writeInterestImage(osgLoA::LoANode& node, const loa::CameraChoice& camera, int width, int height,
                        const std::string& path);

#endif
