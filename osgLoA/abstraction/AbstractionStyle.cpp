/* osgLoA - level-of-abstraction visualization for OpenSceneGraph. MIT licence. */
#include <osgLoA/abstraction/AbstractionStyle>

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace osgLoA
{

namespace
{
/** GLSL's mix: a (1 - t) + b t. */
float mix(float a, float b, float t)
{
    return a * (1.0f - t) + b * t;
}

[[noreturn]] void refuse(const std::string& field, const std::string& value, const std::string& range)
{
    throw std::invalid_argument("AbstractionStyle: " + field + " " + value + " is outside " + range);
}

void checkInt(const char* field, int v, int lo, int hi)
{
    if (v < lo || v > hi)
        refuse(field, std::to_string(v), "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
}

/** v in [lo, hi], or in (lo, hi] with openLow; NaN fails. */
void checkFloat(const char* field, float v, float lo, float hi, bool openLow = false)
{
    const bool ok = std::isfinite(v) && (openLow ? v > lo : v >= lo) && v <= hi;
    if (!ok)
    {
        char range[64];
        std::snprintf(range, sizeof(range), "%s%g, %g]", openLow ? "(" : "[", double(lo), double(hi));
        refuse(field, std::to_string(v), range);
    }
}

void checkEnum(const char* field, int v, int count)
{
    if (v < 0 || v >= count) refuse(field, std::to_string(v), "its enumerators");
}
} // namespace

const std::vector<std::string>& AbstractionStyle::builtinNames()
{
    static const std::vector<std::string> names = {"dog",
                                                   "kuwahara3",
                                                   "kuwahara5",
                                                   "kuwahara-dog",
                                                   "adaptive",
                                                   "adaptive-segmented",
                                                   "cel",
                                                   "pencil",
                                                   "sobel",
                                                   "canny",
                                                   "hybrid-toon",
                                                   "hybrid-pencil",
                                                   "adaptive-hybrid-toon",
                                                   "adaptive-hybrid-pencil"};
    return names;
}

osg::ref_ptr<AbstractionStyle> AbstractionStyle::createBuiltin(const std::string& name)
{
    osg::ref_ptr<AbstractionStyle> s = new AbstractionStyle;
    s->setName(name);
    // The painterly filter of the hybrids: "3x3 sampled regions" (radius 2), one iteration.
    auto hybrid = [&](Shading shading, Combination combination)
    {
        s->setNormalPass(UNSHADED);
        s->setShading(shading);
        s->setKuwaharaRadius(2);
        s->setKuwaharaIterations(1);
        s->setCombination(combination);
    };
    // Paper 002 §4: object importance from object-space distance to the focus object.
    auto objectFocus = [&]()
    {
        s->setAdaptivity(OBJECT_FOCUS);
        s->getFocus()->setMode(AbstractionFocus::OBJECT);
        s->getFocus()->setInnerRadius(0.05f);
        s->getFocus()->setOuterRadius(0.3f);
        s->setKuwaharaIterations(2);
        s->setKuwaharaIterationsFocus(1);
        s->setShadingAtFocus(0.5f);
    };
    if (name == "dog")
    {
        s->setEdgeDetector(DOG);
        s->setEdgeSource(NORMAL_IMAGE);
        s->setDescription("DoG edges of the lit frame over it (paper 001 Fig. 1b)");
    }
    else if (name == "kuwahara3" || name == "kuwahara5")
    {
        s->setKuwaharaRadius(name == "kuwahara3" ? 2 : 4);
        s->setDescription(name == "kuwahara3" ? "Kuwahara filter, 3x3 sampled regions (paper 001 Fig. 1c)"
                                              : "Kuwahara filter, 5x5 sampled regions (paper 001 Table 1)");
    }
    else if (name == "kuwahara-dog")
    {
        s->setKuwaharaRadius(2);
        s->setEdgeDetector(DOG);
        s->setEdgeSource(ABSTRACTED_IMAGE);
        s->setDescription("Kuwahara 3x3 with its DoG edges overlaid (paper 001 Fig. 1d)");
    }
    else if (name == "adaptive" || name == "adaptive-segmented")
    {
        s->setAdaptivity(SCREEN_FOCUS);
        s->setKuwaharaRadius(2);
        s->setKuwaharaIterations(3);
        s->setKuwaharaIterationsFocus(0);
        s->setEdgeDetector(DOG);
        s->setEdgeSource(ABSTRACTED_IMAGE);
        s->setEdgeOpacity(1.0f);
        s->setEdgeOpacityFar(0.1f);
        s->setBleaching(0.6f);
        if (name == "adaptive")
            s->setDescription("Kuwahara 0-3 iterations and DoG edges by screen distance to the focus, "
                              "bleached far away (paper 001 Fig. 3)");
        else
        {
            s->setSegmentation(true);
            s->getFocus()->setMode(AbstractionFocus::OBJECT);
            s->setDescription("adaptive, with the focus object unabstracted (paper 001 Fig. 4)");
        }
    }
    else if (name == "cel")
    {
        s->setNormalPass(UNSHADED);
        s->setShading(CEL);
        s->setCombination(SHADING_ONLY);
        s->setDescription("cel shading: colour x quantized shade, object space only (paper 002 Fig. 3d)");
    }
    else if (name == "pencil")
    {
        s->setNormalPass(UNSHADED);
        s->setShading(PENCIL);
        s->setPencilScale(0.05f); // one 256-texel tile per 20 model units (metres in the demo city)
        s->setCombination(SHADING_ONLY);
        s->setDescription("pencil shading tones, object space only (paper 002 Fig. 3c)");
    }
    else if (name == "sobel" || name == "canny")
    {
        s->setEdgeDetector(name == "sobel" ? SOBEL : CANNY);
        s->setEdgeSource(NORMAL_IMAGE);
        if (name == "canny")
        {
            // Lower than the filter's defaults: after the sigma-1 smoothing a rendered city's
            // luminance gradients rarely reach 0.2 (measured on the demo city).
            s->setCannyLow(0.05f);
            s->setCannyHigh(0.1f);
        }
        s->setDescription(name == "sobel" ? "Sobel edges of the lit frame over it (paper 002 Table 1)"
                                          : "Canny edges of the lit frame over it (paper 002 §3.2)");
    }
    else if (name == "hybrid-toon" || name == "adaptive-hybrid-toon")
    {
        hybrid(CEL, TOON);
        s->setEdgeDetector(SOBEL);
        s->setEdgeSource(NORMAL_IMAGE);
        s->setSilhouettes(true);
        s->setBrightening(1.5f);
        if (name == "hybrid-toon")
            s->setDescription("hybrid toon: Kuwahara x 1.5 x cel shade x Sobel and silhouette edges "
                              "(paper 002 Eq. 1, Fig. 1a)");
        else
        {
            objectFocus();
            s->setCelLevels(3);
            s->setCelLevelsFar(8);
            s->setSobelThreshold(0.1f);
            s->setSobelThresholdFar(0.4f);
            s->setDescription("hybrid toon adapted to object importance: fewer cel shades, more edges, "
                              "less filtering on the focus object (paper 002 Fig. 5a)");
        }
    }
    else if (name == "hybrid-pencil" || name == "adaptive-hybrid-pencil")
    {
        hybrid(PENCIL, PENCIL_SKETCH);
        s->setPencilScale(0.05f);
        s->setPencilGamma(2.0f);
        if (name == "hybrid-pencil")
            s->setDescription("hybrid pencil: Kuwahara x pencil tone^2 (paper 002 Eq. 2, Fig. 1b)");
        else
        {
            objectFocus();
            s->setDescription("hybrid pencil adapted to object importance: more painterly colour, less "
                              "filtering on the focus object (paper 002 Fig. 5b)");
        }
    }
    else
    {
        throw std::invalid_argument("AbstractionStyle::createBuiltin: unknown style name '" + name + "'");
    }
    return s;
}

AbstractionStyle::AbstractionStyle() : _focus(new AbstractionFocus) {}

AbstractionStyle::AbstractionStyle(const AbstractionStyle& o, const osg::CopyOp& copyop)
    : osg::Object(o, copyop), _description(o._description), _normalPass(o._normalPass), _shading(o._shading),
      _celLevels(o._celLevels), _pencilLevels(o._pencilLevels), _ambient(o._ambient),
      _pencilScale(o._pencilScale), _pencilAnisotropy(o._pencilAnisotropy),
      _kuwaharaRadius(o._kuwaharaRadius), _kuwaharaIterations(o._kuwaharaIterations),
      _kuwaharaIterationsFocus(o._kuwaharaIterationsFocus), _edgeDetector(o._edgeDetector),
      _edgeSource(o._edgeSource), _dogSigma(o._dogSigma), _dogRatio(o._dogRatio), _dogTau(o._dogTau),
      _dogEpsilon(o._dogEpsilon),
      _sobelThreshold(o._sobelThreshold), _sobelThresholdFar(o._sobelThresholdFar), _cannyLow(o._cannyLow),
      _cannyHigh(o._cannyHigh), _silhouettes(o._silhouettes), _edgeOpacity(o._edgeOpacity),
      _edgeOpacityFar(o._edgeOpacityFar), _combination(o._combination), _brightening(o._brightening),
      _pencilGamma(o._pencilGamma), _adaptivity(o._adaptivity), _segmentation(o._segmentation),
      _bleaching(o._bleaching), _celLevelsFar(o._celLevelsFar), _shadingAtFocus(o._shadingAtFocus),
      _focus((copyop.getCopyFlags() & osg::CopyOp::DEEP_COPY_OBJECTS)
                 ? new AbstractionFocus(*o._focus, copyop)
                 : o._focus.get())
{
}

void AbstractionStyle::setFocus(AbstractionFocus* focus)
{
    _focus = focus ? focus : new AbstractionFocus;
}

void AbstractionStyle::validate() const
{
    checkEnum("normalPass", _normalPass, 2);
    checkEnum("shading", _shading, 3);
    checkInt("celLevels", _celLevels, 2, 16);
    checkInt("pencilLevels", _pencilLevels, 2, 8);
    checkFloat("ambient", _ambient, 0.0f, 1.0f);
    checkFloat("pencilScale", _pencilScale, 0.0f, 64.0f, true);
    checkFloat("pencilAnisotropy", _pencilAnisotropy, 1.0f, 16.0f);
    if (_kuwaharaRadius != 0) checkInt("kuwaharaRadius", _kuwaharaRadius, 1, 16);
    checkInt("kuwaharaIterations", _kuwaharaIterations, 1, 3);
    checkInt("kuwaharaIterationsFocus", _kuwaharaIterationsFocus, 0, _kuwaharaIterations);
    checkEnum("edgeDetector", _edgeDetector, 4);
    checkEnum("edgeSource", _edgeSource, 2);
    checkFloat("dogSigma", _dogSigma, 0.0f, 8.0f, true);
    checkFloat("dogRatio", _dogRatio, 1.0f, 4.0f, true);
    checkFloat("dogTau", _dogTau, 0.0f, 1.0f);
    checkFloat("dogEpsilon", _dogEpsilon, -10.0f, 10.0f);
    checkFloat("sobelThreshold", _sobelThreshold, 0.0f, 4.0f, true);
    checkFloat("sobelThresholdFar", _sobelThresholdFar, 0.0f, 4.0f, true);
    checkFloat("cannyLow", _cannyLow, 0.0f, 4.0f);
    checkFloat("cannyHigh", _cannyHigh, 0.0f, 4.0f);
    if (_cannyLow > _cannyHigh)
        throw std::invalid_argument("AbstractionStyle: cannyLow " + std::to_string(_cannyLow) +
                                    " is above cannyHigh " + std::to_string(_cannyHigh));
    checkFloat("edgeOpacity", _edgeOpacity, 0.0f, 1.0f);
    checkFloat("edgeOpacityFar", _edgeOpacityFar, 0.0f, 1.0f);
    checkEnum("combination", _combination, 4);
    checkFloat("brightening", _brightening, 0.0f, 4.0f);
    checkFloat("pencilGamma", _pencilGamma, 0.1f, 8.0f);
    checkEnum("adaptivity", _adaptivity, 3);
    checkFloat("bleaching", _bleaching, 0.0f, 1.0f);
    checkInt("celLevelsFar", _celLevelsFar, 2, 16);
    checkFloat("shadingAtFocus", _shadingAtFocus, 0.0f, 1.0f);
    _focus->validate();
}

bool AbstractionStyle::needsIdPass() const
{
    return _silhouettes || _segmentation || _adaptivity == OBJECT_FOCUS;
}

bool AbstractionStyle::needsShadingPass() const
{
    return _shading != NO_SHADING;
}

bool AbstractionStyle::needsPainterly() const
{
    return _kuwaharaRadius > 0;
}

bool AbstractionStyle::needsEdges() const
{
    return _edgeDetector != NO_EDGES || _silhouettes;
}

AbstractionStyle::PixelParameters AbstractionStyle::pixelParameters(float phi) const
{
    if (!(phi > 0.0f) || _adaptivity == UNIFORM) phi = 0.0f; // NaN and negatives too
    if (phi > 1.0f) phi = 1.0f;
    const bool object = _adaptivity == OBJECT_FOCUS;
    PixelParameters p;
    p.lambda = mix(float(_kuwaharaIterations), float(_kuwaharaIterationsFocus), phi);
    p.edgeOpacity = _adaptivity == SCREEN_FOCUS ? mix(_edgeOpacityFar, _edgeOpacity, phi) : _edgeOpacity;
    p.bleach = _bleaching * (1.0f - phi);
    p.celLevels =
        object ? int(std::floor(mix(float(_celLevelsFar), float(_celLevels), phi) + 0.5f)) : _celLevels;
    p.sobelThreshold = object ? mix(_sobelThresholdFar, _sobelThreshold, phi) : _sobelThreshold;
    p.shadingShare = object ? mix(1.0f, _shadingAtFocus, phi) : 1.0f;
    return p;
}

} // namespace osgLoA
