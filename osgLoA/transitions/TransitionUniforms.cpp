// TransitionUniforms: the uniform contract of shaders/loa_transition.frag.glsl.
#include <osgLoA/transitions/TransitionUniforms>

#include <osg/Uniform>

namespace osgLoA
{

namespace
{
constexpr unsigned kN = UsageScenario::kMaxConfigurations;

osg::Uniform* uniform(osg::StateSet& ss, const char* name, osg::Uniform::Type type, unsigned n = 1)
{
    return ss.getOrCreateUniform(name, type, n);
}
} // namespace

void TransitionUniforms::applyScenario(osg::StateSet& ss, const ScenarioEvaluator& evaluator)
{
    const UsageScenario* s = evaluator.getScenario();
    if (!s) return;
    const auto& configs = s->getConfigurations();
    const unsigned n = unsigned(std::min<std::size_t>(configs.size(), kN));
    uniform(ss, "loa_numConfigurations", osg::Uniform::INT)->set(int(n));
    osg::Uniform* fade = uniform(ss, "loa_fade", osg::Uniform::FLOAT_VEC4, kN);
    osg::Uniform* mode = uniform(ss, "loa_mode", osg::Uniform::INT_VEC4, kN);
    osg::Uniform* weight = uniform(ss, "loa_metricWeight", osg::Uniform::FLOAT_VEC4, kN);
    osg::Uniform* interestWeight = uniform(ss, "loa_interestWeight", osg::Uniform::FLOAT, kN);
    for (unsigned j = 0; j < n; ++j)
    {
        const TransitionConfiguration& c = *configs[j];
        const BlendFunction b = c.getBlendFunction();
        fade->setElement(j, osg::Vec4f(b.inBegin, b.inEnd, b.outBegin, b.outEnd));
        int present = 0;
        float w[SaliencyMetric::kNumKinds] = {};
        for (const auto& m : c.getMetrics())
        {
            if (!m.valid()) continue;
            present |= 1 << m->getKind();
            w[m->getKind()] = float(m->getWeight());
        }
        mode->setElement(j, int(c.getInterpolation()), int(c.getCombination()), present, 0);
        weight->setElement(j, osg::Vec4f(w[0], w[1], w[2], w[3]));
        interestWeight->setElement(j, w[SaliencyMetric::FEATURE_INTEREST]);
    }
    applyRamps(ss, evaluator);
    // Interest groups: fragment-mode configurations whose interest is the same function (same
    // metrics, weights, ramps and combination) share one evaluation per fragment. With at most
    // kMaxInterestGroups of them the shader is specialized at compile time (LOA_INTEREST_GROUPS,
    // LOA_METRICS: the metric kinds present), so a fragment computes each group's interest once
    // and nothing for object-mode configurations or absent metrics; llvmpipe executes both sides
    // of every branch, so run-time tests would not spare it the work. More groups: the generic
    // path, one evaluation per configuration.
    osg::Uniform* group = uniform(ss, "loa_interestGroup", osg::Uniform::INT, kN);
    osg::Uniform* groupConfig = uniform(ss, "loa_groupConfiguration", osg::Uniform::INT, kMaxInterestGroups);
    std::vector<unsigned> representatives;
    int metrics = 0;
    for (unsigned j = 0; j < n; ++j)
    {
        const TransitionConfiguration& c = *configs[j];
        int g = -1;
        if (c.getInterpolation() == TransitionConfiguration::FRAGMENT)
        {
            for (unsigned r = 0; r < representatives.size() && g < 0; ++r)
                if (configs[representatives[r]]->hasSameInterestAs(c)) g = int(r);
            if (g < 0)
            {
                g = int(representatives.size());
                representatives.push_back(j);
            }
            for (const auto& m : c.getMetrics())
                if (m.valid()) metrics |= 1 << m->getKind();
        }
        group->setElement(j, g);
    }
    for (unsigned r = 0; r < kMaxInterestGroups; ++r)
        groupConfig->setElement(r, r < representatives.size() ? int(representatives[r]) : 0);
    if (representatives.size() <= kMaxInterestGroups)
    {
        ss.setDefine("LOA_INTEREST_GROUPS", std::to_string(representatives.size()));
        ss.setDefine("LOA_METRICS", std::to_string(metrics));
    }
    else
    {
        ss.removeDefine("LOA_INTEREST_GROUPS");
        ss.removeDefine("LOA_METRICS");
    }

    const osg::BoundingBoxd& focus = evaluator.getView().focus;
    uniform(ss, "loa_hasFocus", osg::Uniform::BOOL)->set(focus.valid());
    if (focus.valid())
    {
        uniform(ss, "loa_focusMin", osg::Uniform::FLOAT_VEC3)->set(osg::Vec3f(focus._min));
        uniform(ss, "loa_focusMax", osg::Uniform::FLOAT_VEC3)->set(osg::Vec3f(focus._max));
    }
    if (!ss.getUniform("loa_hasRegionMap")) uniform(ss, "loa_hasRegionMap", osg::Uniform::BOOL)->set(false);
}

void TransitionUniforms::applyRamps(osg::StateSet& ss, const ScenarioEvaluator& evaluator)
{
    const UsageScenario* s = evaluator.getScenario();
    if (!s) return;
    const auto& configs = s->getConfigurations();
    const unsigned n = unsigned(std::min<std::size_t>(configs.size(), kN));
    osg::Uniform* rampA = uniform(ss, "loa_rampA", osg::Uniform::FLOAT_VEC4, kN);
    osg::Uniform* rampB = uniform(ss, "loa_rampB", osg::Uniform::FLOAT_VEC4, kN);
    for (unsigned j = 0; j < n; ++j)
    {
        osg::Vec2f ramp[SaliencyMetric::kNumKinds];
        for (const auto& m : configs[j]->getMetrics())
            if (m.valid()) ramp[m->getKind()].set(float(m->getNear()), float(m->getFar()));
        rampA->setElement(j, osg::Vec4f(ramp[0].x(), ramp[0].y(), ramp[1].x(), ramp[1].y()));
        rampB->setElement(j, osg::Vec4f(ramp[2].x(), ramp[2].y(), ramp[3].x(), ramp[3].y()));
    }
}

void TransitionUniforms::applyEye(osg::StateSet& ss, const osg::Vec3d& eye)
{
    uniform(ss, "loa_eye", osg::Uniform::FLOAT_VEC3)->set(osg::Vec3f(eye));
}

void TransitionUniforms::applyWorldToScene(osg::StateSet& ss, const osg::Matrixd& worldToScene)
{
    uniform(ss, "loa_worldToScene", osg::Uniform::FLOAT_MAT4)->set(osg::Matrixf(worldToScene));
}

void TransitionUniforms::applyRegionMap(osg::StateSet& ss, osg::Texture2D* map, const osg::Vec2d& origin,
                                        const osg::Vec2d& extent, double scale)
{
    uniform(ss, "loa_hasRegionMap", osg::Uniform::BOOL)->set(map != nullptr);
    if (!map) return;
    ss.setTextureAttributeAndModes(kRegionMapUnit, map, osg::StateAttribute::ON);
    uniform(ss, "loa_regionMap", osg::Uniform::SAMPLER_2D)->set(int(kRegionMapUnit));
    uniform(ss, "loa_regionMapFrame", osg::Uniform::FLOAT_VEC4)
        ->set(osg::Vec4f(float(origin.x()), float(origin.y()), float(1.0 / extent.x()),
                         float(1.0 / extent.y())));
    uniform(ss, "loa_regionMapScale", osg::Uniform::FLOAT)->set(float(scale));
}

void TransitionUniforms::applyFeature(osg::StateSet& ss, const ScenarioEvaluator& evaluator,
                                      const ScenarioEvaluator::FeatureState& feature)
{
    int mask = 0;
    osg::Uniform* weights = uniform(ss, "loa_featureWeights", osg::Uniform::FLOAT, kN);
    osg::Uniform* interests = uniform(ss, "loa_featureInterests", osg::Uniform::FLOAT, kN);
    const ScenarioEvaluator::Match* m = evaluator.matchesOf(feature);
    for (unsigned k = 0; k < feature.numMatches; ++k)
    {
        if (m[k].configuration >= kN) continue;
        mask |= 1 << m[k].configuration;
        weights->setElement(m[k].configuration, m[k].rawWeight);
        interests->setElement(m[k].configuration, m[k].interest);
    }
    uniform(ss, "loa_featureMatches", osg::Uniform::INT)->set(mask);
    uniform(ss, "loa_featureInterest", osg::Uniform::FLOAT)->set(feature.staticInterest);
}

} // namespace osgLoA
