// StreetLabels: street names along their centre lines in signed-distance-field text.
#include <osgLoA/render/ShaderLibrary>
#include <osgLoA/semantics/FeatureIndex>
#include <osgLoA/styles/GraphicStyle>
#include <osgLoA/styles/StreetLabels>
#include <osgLoA/styles/StreetPresentation>

#include "../util/TriangleCollector.h"

#include <osg/BlendFunc>
#include <osg/Depth>
#include <osgUtil/CullVisitor>

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <stdexcept>

namespace osgLoA
{

namespace
{
const double kLabelPi = 3.14159265358979323846;

double wrapAngle(double a)
{
    while (a > kLabelPi)
        a -= 2.0 * kLabelPi;
    while (a <= -kLabelPi)
        a += 2.0 * kLabelPi;
    return a;
}

/** The size factor of a road class (major 1, minor 0.9, path and rail 0.8). */
double classFactor(int roadClass)
{
    switch (roadClass)
    {
    case StreetPresentation::MAJOR:
        return 1.0;
    case StreetPresentation::MINOR:
    case StreetPresentation::UNKNOWN:
        return 0.9;
    default:
        return 0.8;
    }
}

struct Vertex
{
    osg::Vec4d clip;
    osg::Vec2d win;
    osg::Vec3d scene;
};

/** A visible stretch of a projected centre line with cumulative window lengths. */
struct Run
{
    std::size_t street = 0;
    std::vector<Vertex> v;
    std::vector<double> s;
    std::vector<double> turn; ///< the window angle the line turns by at each vertex
    double length() const { return s.empty() ? 0.0 : s.back(); }
};

struct Projector
{
    const StreetLabels::View& view;
    Vertex vertex(const osg::Vec3d& scene, const osg::Vec4d& clip) const
    {
        Vertex r;
        r.clip = clip;
        r.scene = scene;
        r.win = osg::Vec2d((clip.x() / clip.w() * 0.5 + 0.5) * view.width,
                           (clip.y() / clip.w() * 0.5 + 0.5) * view.height);
        return r;
    }
    osg::Vec4d clipOf(const osg::Vec3d& p) const { return osg::Vec4d(p, 1.0) * view.sceneToClip; }
    double depth(const osg::Vec4d& clip) const { return clip.z() / clip.w() * 0.5 + 0.5; }
};

/** Where arc length s lies on a run: the window point, the scene point (perspective-correct)
 *  and its clip coordinates. */
struct Along
{
    osg::Vec2d win;
    osg::Vec3d scene;
    osg::Vec4d clip;
    std::size_t segment = 0;
};

Along along(const Run& r, double s)
{
    Along a;
    s = std::max(0.0, std::min(s, r.length()));
    std::size_t k = std::size_t(std::upper_bound(r.s.begin(), r.s.end(), s) - r.s.begin());
    k = k == 0 ? 0 : k - 1;
    if (k + 1 >= r.v.size()) k = r.v.size() - 2;
    const Vertex &A = r.v[k], &B = r.v[k + 1];
    const double len = r.s[k + 1] - r.s[k];
    const double t = len > 0.0 ? (s - r.s[k]) / len : 0.0;
    // Window positions are linear in t, the scene in u: u = t wA / ((1 - t) wB + t wA).
    const double den = (1.0 - t) * B.clip.w() + t * A.clip.w();
    const double u = den != 0.0 ? t * A.clip.w() / den : t;
    a.win = A.win * (1.0 - t) + B.win * t;
    a.scene = A.scene * (1.0 - u) + B.scene * u;
    a.clip = A.clip * (1.0 - u) + B.clip * u;
    a.segment = k;
    return a;
}

/** Separating-axis test of two convex quads (corners in order). */
bool overlap(const osg::Vec2d a[4], const osg::Vec2d b[4])
{
    for (const osg::Vec2d* q : {a, b})
        for (int e = 0; e < 2; ++e)
        {
            const osg::Vec2d edge = q[e + 1] - q[e];
            const osg::Vec2d n(-edge.y(), edge.x());
            double amin = 1e300, amax = -1e300, bmin = 1e300, bmax = -1e300;
            for (int i = 0; i < 4; ++i)
            {
                const double pa = a[i] * n, pb = b[i] * n;
                amin = std::min(amin, pa);
                amax = std::max(amax, pa);
                bmin = std::min(bmin, pb);
                bmax = std::max(bmax, pb);
            }
            if (amax <= bmin || bmax <= amin) return false;
        }
    return true;
}

void corners(const osg::Vec2d& centre, double angle, double x0, double y0, double x1, double y1,
             osg::Vec2d c[4])
{
    const double cs = std::cos(angle), sn = std::sin(angle);
    const double xs[4] = {x0, x1, x1, x0}, ys[4] = {y0, y0, y1, y1};
    for (int i = 0; i < 4; ++i)
        c[i] = centre + osg::Vec2d(xs[i] * cs - ys[i] * sn, xs[i] * sn + ys[i] * cs);
}

/** Glyph quads are given in window pixels: no bound in the scene (an OSG bound would be taken
 *  for scene coordinates by the cull's near/far computation and small-feature culling). */
struct NoSceneBound : public osg::Drawable::ComputeBoundingBoxCallback
{
    osg::BoundingBox computeBound(const osg::Drawable&) const override { return osg::BoundingBox(); }
};

template <typename T> void setUniform(osg::StateSet& ss, const char* name, const T& v)
{
    if (osg::Uniform* u = ss.getUniform(name))
        u->set(v);
    else
        ss.addUniform(new osg::Uniform(name, v));
}
} // namespace

bool StreetLabels::parametersOf(const GraphicStyle& style, Parameters& p)
{
    const osg::Uniform* size = style.getParameter("loa_labels_size");
    float v = 0.0f;
    if (!size || !size->get(v) || !(v > 0.0f)) return false;
    p.size = v;
    if (const osg::Uniform* u = style.getParameter("loa_labels_color")) u->get(p.color);
    if (const osg::Uniform* u = style.getParameter("loa_labels_halo")) u->get(p.halo);
    if (const osg::Uniform* u = style.getParameter("loa_labels_haloPixels")) u->get(p.haloPixels);
    if (!(p.haloPixels >= 0.0f)) p.haloPixels = 0.0f;
    return true;
}

void StreetLabels::addUniforms(GraphicStyle& style, const Parameters& p)
{
    osg::StateSet& ss = *style.getParameters();
    setUniform(ss, "loa_labels_size", p.size);
    setUniform(ss, "loa_labels_color", p.color);
    setUniform(ss, "loa_labels_halo", p.halo);
    setUniform(ss, "loa_labels_haloPixels", p.haloPixels);
}

void StreetLabels::addUniforms(GraphicStyle& style)
{
    addUniforms(style, Parameters());
}

std::vector<StreetLabels::Street> StreetLabels::collect(const FeatureIndex& index)
{
    std::vector<Street> streets;
    std::set<const Feature*> seen;
    for (const FeatureIndex::Entry& e : index.entries())
    {
        const Feature& f = *e.feature;
        if (f.getType() != FeatureType::Street || f.getLabel().empty() || f.getCentreline().size() < 2 ||
            !seen.insert(&f).second)
            continue;
        osg::ref_ptr<osg::Node> node;
        if (!e.node.lock(node)) continue;
        osg::NodePath path = index.pathOf(e);
        const osg::Matrixd toRoot = osg::computeLocalToWorld(path);
        path.pop_back();
        TriangleCollector triangles(osg::computeLocalToWorld(path));
        node->accept(triangles);
        const std::vector<osg::Vec3d>& t = triangles.corners();

        Street s;
        s.featureId = f.getId();
        s.label = f.getLabel();
        s.text = SignedDistanceFont::decodeUtf8(s.label);
        const double top = f.getBound().valid() ? double(f.getBound().zMax()) : 0.0;
        double length = 0.0;
        for (const osg::Vec2d& c : f.getCentreline())
        {
            osg::Vec3d w = osg::Vec3d(c.x(), c.y(), 0.0) * toRoot;
            if (!std::isfinite(w.x()) || !std::isfinite(w.y())) continue;
            // The highest surface under the point (barycentric, in x and y).
            bool hit = false;
            double z = 0.0;
            for (std::size_t i = 0; i + 2 < t.size(); i += 3)
            {
                const osg::Vec3d &a = t[i], &b = t[i + 1], &cc = t[i + 2];
                const double det = (b.y() - cc.y()) * (a.x() - cc.x()) + (cc.x() - b.x()) * (a.y() - cc.y());
                if (std::fabs(det) < 1e-12) continue;
                const double l0 =
                    ((b.y() - cc.y()) * (w.x() - cc.x()) + (cc.x() - b.x()) * (w.y() - cc.y())) / det;
                const double l1 =
                    ((cc.y() - a.y()) * (w.x() - cc.x()) + (a.x() - cc.x()) * (w.y() - cc.y())) / det;
                const double l2 = 1.0 - l0 - l1;
                const double eps = -1e-9;
                if (l0 < eps || l1 < eps || l2 < eps) continue;
                const double zi = l0 * a.z() + l1 * b.z() + l2 * cc.z();
                if (!hit || zi > z) z = zi;
                hit = true;
            }
            w.z() = hit ? z : top;
            if (!s.points.empty())
                length += osg::Vec2d(w.x() - s.points.back().x(), w.y() - s.points.back().y()).length();
            s.points.push_back(w);
        }
        if (s.points.size() < 2 || !(length > 0.0)) continue;
        double area = 0.0;
        for (std::size_t i = 0; i + 2 < t.size(); i += 3)
        {
            const osg::Vec3d u = t[i + 1] - t[i], v = t[i + 2] - t[i];
            area += 0.5 * std::fabs(u.x() * v.y() - u.y() * v.x());
        }
        s.width = area / length;
        s.roadClass = int(StreetPresentation::classOf(f.getSubType(), s.width));
        streets.push_back(std::move(s));
    }
    return streets;
}

void StreetLabels::glyphQuad(const PlacedGlyph& g, double size, const SignedDistanceFont& font,
                             osg::Vec2d c[4])
{
    const SignedDistanceFont::Glyph* glyph = font.glyph(g.code);
    if (!glyph)
    {
        for (int i = 0; i < 4; ++i)
            c[i] = g.centre;
        return;
    }
    // The pen: half the advance before the centre, the baseline half the cap height below.
    const double penX = -0.5 * glyph->advance, penY = -0.5 * font.capHeight();
    corners(g.centre, g.angle, size * (penX + glyph->quadMin.x()), size * (penY + glyph->quadMin.y()),
            size * (penX + glyph->quadMax.x()), size * (penY + glyph->quadMax.y()), c);
}

void StreetLabels::glyphBox(const PlacedGlyph& g, double size, const SignedDistanceFont& font, double padding,
                            osg::Vec2d c[4])
{
    const SignedDistanceFont::Glyph* glyph = font.glyph(g.code);
    const double halfX = 0.5 * size * (glyph ? glyph->advance : 0.5) + padding;
    const double halfY = size * (0.5 * font.capHeight() + 0.25) + padding;
    corners(g.centre, g.angle, -halfX, -halfY, halfX, halfY, c);
}

std::vector<StreetLabels::Label> StreetLabels::layout(const std::vector<Street>& streets, const View& view,
                                                      const SignedDistanceFont& font, const Parameters& p,
                                                      const OpacityFunction& opacity, Statistics* stats)
{
    Statistics st;
    std::vector<Label> labels;
    if (!(p.size > 0.0f) || !(view.width > 0.0) || !(view.height > 0.0))
    {
        if (stats) *stats = st;
        return labels;
    }
    const Projector proj{view};

    // 1. The visible runs of every centre line (clipped at the near plane: z + w >= 0).
    std::vector<Run> runs;
    for (std::size_t si = 0; si < streets.size(); ++si)
    {
        const Street& street = streets[si];
        Run run;
        run.street = si;
        auto close = [&]()
        {
            if (run.v.size() >= 2) runs.push_back(run);
            run.v.clear();
        };
        for (std::size_t i = 0; i + 1 < street.points.size(); ++i)
        {
            const osg::Vec3d &a = street.points[i], &b = street.points[i + 1];
            const osg::Vec4d ca = proj.clipOf(a), cb = proj.clipOf(b);
            const double da = ca.z() + ca.w(), db = cb.z() + cb.w();
            if (da < 0.0 && db < 0.0)
            {
                close();
                continue;
            }
            double t0 = 0.0, t1 = 1.0;
            if (da < 0.0) t0 = da / (da - db);
            if (db < 0.0) t1 = da / (da - db);
            const osg::Vec3d pa = a + (b - a) * t0, pb = a + (b - a) * t1;
            const osg::Vec4d qa = ca + (cb - ca) * t0, qb = ca + (cb - ca) * t1;
            if (!(qa.w() > 0.0) || !(qb.w() > 0.0))
            {
                close();
                continue;
            }
            if (run.v.empty() || t0 > 0.0)
            {
                close();
                run.v.push_back(proj.vertex(pa, qa));
            }
            run.v.push_back(proj.vertex(pb, qb));
            if (t1 < 1.0) close();
        }
        close();
    }
    for (Run& r : runs)
    {
        r.s.assign(1, 0.0);
        r.turn.assign(r.v.size(), 0.0);
        for (std::size_t i = 1; i < r.v.size(); ++i)
        {
            r.s.push_back(r.s.back() + (r.v[i].win - r.v[i - 1].win).length());
            if (i + 1 < r.v.size())
            {
                const osg::Vec2d a = r.v[i].win - r.v[i - 1].win, b = r.v[i + 1].win - r.v[i].win;
                r.turn[i] = std::fabs(std::atan2(a.x() * b.y() - a.y() * b.x(), a * b));
            }
        }
    }
    // 2. Priority: major streets first, then the longest on screen (then the street's order).
    std::vector<std::size_t> order(runs.size());
    for (std::size_t i = 0; i < order.size(); ++i)
        order[i] = i;
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b)
                     {
                         const int ca = streets[runs[a].street].roadClass,
                                   cb = streets[runs[b].street].roadClass;
                         const int ka = ca < 0 ? 1 : ca, kb = cb < 0 ? 1 : cb;
                         if (ka != kb) return ka < kb;
                         return runs[a].length() > runs[b].length();
                     });

    std::vector<std::array<osg::Vec2d, 4>> placedBoxes;
    std::vector<std::pair<osg::Vec2d, osg::Vec2d>> placedExtents; // per label: min, max of its boxes
    std::vector<std::size_t> labelOfExtent;
    const double maxTurn = double(p.maxTurnDegrees) * kLabelPi / 180.0;
    for (std::size_t oi : order)
    {
        const Run& run = runs[oi];
        const Street& street = streets[run.street];
        if (street.text.empty()) continue;
        const double classSize = double(p.size) * classFactor(street.roadClass);
        // The text's width in em (advances and kerning).
        std::vector<double> pen(street.text.size());
        double textEm = 0.0;
        for (std::size_t i = 0; i < street.text.size(); ++i)
        {
            if (i > 0) textEm += font.kerning(street.text[i - 1], street.text[i]);
            pen[i] = textEm;
            const SignedDistanceFont::Glyph* g = font.glyph(street.text[i]);
            textEm += g ? g->advance : 0.5;
        }
        const double S = run.length();
        if (S < std::min(classSize, double(p.minPixels)) * textEm) continue;
        // The stretch of the run in the viewport (a guard band of a label's length around it): a
        // line reaching just past the near plane runs far outside the window, where no label can
        // go. Candidates are tried there only.
        double s0 = S, s1 = 0.0;
        {
            const double band = classSize * textEm;
            const double x0 = -band, y0 = -band, x1 = view.width + band, y1 = view.height + band;
            for (std::size_t i = 0; i + 1 < run.v.size(); ++i)
            {
                // Liang-Barsky: the part of segment i inside the band rectangle.
                const osg::Vec2d a = run.v[i].win, d = run.v[i + 1].win - a;
                double t0 = 0.0, t1 = 1.0;
                bool inside = true;
                const double ps[4] = {-d.x(), d.x(), -d.y(), d.y()};
                const double qs[4] = {a.x() - x0, x1 - a.x(), a.y() - y0, y1 - a.y()};
                for (int e = 0; e < 4 && inside; ++e)
                {
                    if (ps[e] == 0.0)
                        inside = qs[e] >= 0.0;
                    else
                    {
                        const double t = qs[e] / ps[e];
                        if (ps[e] < 0.0)
                            t0 = std::max(t0, t);
                        else
                            t1 = std::min(t1, t);
                        inside = t0 <= t1;
                    }
                }
                if (!inside) continue;
                const double len = run.s[i + 1] - run.s[i];
                s0 = std::min(s0, run.s[i] + t0 * len);
                s1 = std::max(s1, run.s[i] + t1 * len);
            }
        }
        if (s1 - s0 < std::min(classSize, double(p.minPixels)) * textEm) continue;
        ++st.streets;
        const double step = std::max(8.0, 0.25 * classSize * textEm);
        const double middle = 0.5 * (s0 + s1);
        for (int k = 0;; ++k)
        {
            // 0, +1, -1, +2, -2, ... steps from the middle of the visible stretch.
            const double offset = step * double((k + 1) / 2) * (k % 2 ? 1.0 : -1.0);
            if (std::fabs(offset) > 0.5 * (s1 - s0)) break;
            const double sc = middle + offset;
            ++st.candidates;
            const Along anchor = along(run, sc);
            // The size: the street's width in pixels at the anchor, clamped.
            double size = classSize;
            if (street.width > 0.0)
            {
                const osg::Vec3d dir = run.v[anchor.segment + 1].scene - run.v[anchor.segment].scene;
                osg::Vec3d side(-dir.y(), dir.x(), 0.0);
                if (side.normalize() > 0.0)
                {
                    const osg::Vec4d c0 = proj.clipOf(anchor.scene - side * (0.5 * street.width));
                    const osg::Vec4d c1 = proj.clipOf(anchor.scene + side * (0.5 * street.width));
                    if (c0.w() > 0.0 && c1.w() > 0.0)
                    {
                        const double widthPixels =
                            (proj.vertex(osg::Vec3d(), c0).win - proj.vertex(osg::Vec3d(), c1).win).length();
                        size = std::min(classSize,
                                        std::max(double(p.minPixels), double(p.widthFactor) * widthPixels));
                    }
                }
            }
            const double L = size * textEm;
            if (sc - 0.5 * L < 0.0 || sc + 0.5 * L > S) continue;
            // Straight enough: no vertex under the label turns by more than maxTurn, all together
            // by no more than twice that.
            double turned = 0.0;
            bool sharp = false;
            for (std::size_t vi = 1; vi + 1 < run.v.size(); ++vi)
                if (run.s[vi] > sc - 0.5 * L && run.s[vi] < sc + 0.5 * L)
                {
                    turned += run.turn[vi];
                    sharp = sharp || run.turn[vi] > maxTurn;
                }
            if (sharp || turned > 2.0 * maxTurn) continue;
            const osg::Vec2d chord = along(run, sc + 0.5 * L).win - along(run, sc - 0.5 * L).win;
            const double chordAngle = std::atan2(chord.y(), chord.x());
            const bool reversed = chordAngle > 0.5 * kLabelPi + 1e-9 || chordAngle <= -0.5 * kLabelPi + 1e-9;
            Label label;
            label.street = run.street;
            label.size = size;
            label.opacity = 1.0f;
            label.anchor = anchor.win;
            label.sceneAnchor = anchor.scene;
            label.reversed = reversed;
            bool ok = true;
            double firstAngle = 0.0, previousAngle = 0.0;
            bool first = true;
            for (std::size_t i = 0; i < street.text.size() && ok; ++i)
            {
                const SignedDistanceFont::Glyph* g = font.glyph(street.text[i]);
                const double adv = size * (g ? g->advance : 0.5);
                const double offsetInLabel = size * pen[i] + 0.5 * adv;
                const double si = reversed ? sc + 0.5 * L - offsetInLabel : sc - 0.5 * L + offsetInLabel;
                const double h = std::max(0.5 * adv, 1.0);
                osg::Vec2d tangent = along(run, si + h).win - along(run, si - h).win;
                if (reversed) tangent = -tangent;
                const double angle = std::atan2(tangent.y(), tangent.x());
                if (!first)
                {
                    if (std::fabs(wrapAngle(angle - previousAngle)) > maxTurn ||
                        std::fabs(wrapAngle(angle - firstAngle)) > 2.0 * maxTurn)
                        ok = false;
                }
                else
                    firstAngle = angle;
                first = false;
                previousAngle = angle;
                if (!g || g->blank) continue;
                const Along at = along(run, si);
                PlacedGlyph pg;
                pg.code = street.text[i];
                pg.centre = at.win;
                pg.angle = angle;
                pg.depth = proj.depth(at.clip);
                osg::Vec2d q[4];
                glyphQuad(pg, size, font, q);
                for (const osg::Vec2d& c : q)
                    if (c.x() < 0.0 || c.y() < 0.0 || c.x() > view.width || c.y() > view.height) ok = false;
                label.glyphs.push_back(pg);
            }
            if (!ok || label.glyphs.empty()) continue;
            // The opacity last: it evaluates the scenario's metrics at the anchor.
            const float o = opacity ? opacity(run.street, anchor.scene) : 1.0f;
            if (!(o >= p.minOpacity)) continue;
            label.opacity = std::min(1.0f, o);
            bool repeated = false;
            for (const Label& other : labels)
                if (streets[other.street].label == street.label &&
                    (other.anchor - label.anchor).length() < double(p.repeatPixels))
                    repeated = true;
            if (repeated) continue;
            // Collisions: the label's extent against each placed label's, then glyph by glyph.
            std::vector<std::array<osg::Vec2d, 4>> boxes;
            osg::Vec2d lo(1e300, 1e300), hi(-1e300, -1e300);
            for (const PlacedGlyph& g : label.glyphs)
            {
                std::array<osg::Vec2d, 4> b;
                glyphBox(g, size, font, p.paddingPixels, b.data());
                for (const osg::Vec2d& c : b)
                {
                    lo = osg::Vec2d(std::min(lo.x(), c.x()), std::min(lo.y(), c.y()));
                    hi = osg::Vec2d(std::max(hi.x(), c.x()), std::max(hi.y(), c.y()));
                }
                boxes.push_back(b);
            }
            bool collides = false;
            std::size_t firstBox = 0;
            for (std::size_t l = 0; l < placedExtents.size() && !collides; ++l)
            {
                const std::size_t boxesEnd =
                    l + 1 < labelOfExtent.size() ? labelOfExtent[l + 1] : placedBoxes.size();
                const auto& e = placedExtents[l];
                firstBox = labelOfExtent[l];
                if (e.second.x() <= lo.x() || hi.x() <= e.first.x() || e.second.y() <= lo.y() ||
                    hi.y() <= e.first.y())
                    continue;
                for (std::size_t b = firstBox; b < boxesEnd && !collides; ++b)
                    for (const auto& mine : boxes)
                        if (overlap(mine.data(), placedBoxes[b].data()))
                        {
                            collides = true;
                            break;
                        }
            }
            if (collides)
            {
                ++st.collisions;
                continue;
            }
            placedExtents.emplace_back(lo, hi);
            labelOfExtent.push_back(placedBoxes.size());
            placedBoxes.insert(placedBoxes.end(), boxes.begin(), boxes.end());
            labels.push_back(std::move(label));
            ++st.labels;
        }
    }
    if (stats) *stats = st;
    return labels;
}

// --- drawing ---------------------------------------------------------------------------------

StreetLabels::StreetLabels(const std::vector<Street>& streets, const std::string& fontFile)
    : _streets(streets)
{
    const std::string file = fontFile.empty() ? SignedDistanceFont::defaultFontFile() : fontFile;
    if (file.empty())
        throw std::runtime_error("street labels need a font: DejaVu Sans was not found (install the Debian "
                                 "package fonts-dejavu-core, or name a font file in LOA_LABEL_FONT)");
    _font = new SignedDistanceFont(file);
    std::vector<unsigned> codes;
    for (const Street& s : _streets)
        codes.insert(codes.end(), s.text.begin(), s.text.end());
    std::sort(codes.begin(), codes.end());
    codes.erase(std::unique(codes.begin(), codes.end()), codes.end());
    _font->require(codes);

    _state = new osg::StateSet;
    _state->setName("osgLoA.StreetLabels");
    _state->setDataVariance(osg::Object::DYNAMIC);
    _state->setAttributeAndModes(
        ShaderLibrary::createProgram("street labels",
                                     {"loa_street_labels.vert.glsl", "loa_street_labels.frag.glsl"})
            .get());
    _state->setAttributeAndModes(new osg::BlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA),
                                 osg::StateAttribute::ON | osg::StateAttribute::OVERRIDE |
                                     osg::StateAttribute::PROTECTED);
    _state->setAttributeAndModes(new osg::Depth(osg::Depth::ALWAYS, 0.0, 1.0, false),
                                 osg::StateAttribute::OFF | osg::StateAttribute::OVERRIDE |
                                     osg::StateAttribute::PROTECTED);
    _state->setMode(GL_CULL_FACE, osg::StateAttribute::OFF | osg::StateAttribute::OVERRIDE |
                                      osg::StateAttribute::PROTECTED);
    _state->setRenderBinDetails(1001, "RenderBin");
    _state->setTextureAttribute(0, _font->getTexture());
    _state->addUniform(new osg::Uniform("loa_labelAtlas", 0));
    _state->addUniform(new osg::Uniform("loa_labelDepth", 1));
    for (int i = 0; i < 2; ++i)
    {
        _geometries[i] = new osg::Geometry;
        _geometries[i]->setName("osgLoA.StreetLabels.glyphs");
        _geometries[i]->setUseDisplayList(false);
        _geometries[i]->setUseVertexBufferObjects(true);
        _geometries[i]->setDataVariance(osg::Object::DYNAMIC);
        _geometries[i]->setCullingActive(false);
        _geometries[i]->setComputeBoundingBoxCallback(new NoSceneBound);
        _geometries[i]->setVertexArray(new osg::Vec2Array);
        _geometries[i]->setTexCoordArray(0, new osg::Vec2Array, osg::Array::BIND_PER_VERTEX);
        _geometries[i]->setTexCoordArray(1, new osg::Vec4Array, osg::Array::BIND_PER_VERTEX);
        _geometries[i]->setTexCoordArray(2, new osg::Vec2Array, osg::Array::BIND_PER_VERTEX);
        _geometries[i]->setTexCoordArray(3, new osg::Vec2Array, osg::Array::BIND_PER_VERTEX);
        _geometries[i]->addPrimitiveSet(new osg::DrawElementsUInt(GL_TRIANGLES));
        _geodes[i] = new osg::Geode;
        _geodes[i]->setCullingActive(false);
        _geodes[i]->addDrawable(_geometries[i].get());
        _geodes[i]->setStateSet(new osg::StateSet);
        // Every glyph's centre and street depth, for the shader's whole-label visibility test.
        _glyphImages[i] = new osg::Image;
        _glyphTextures[i] = new osg::Texture2D;
        _glyphTextures[i]->setName("osgLoA.StreetLabels.glyphCentres");
        _glyphTextures[i]->setInternalFormat(GL_RGBA32F_ARB);
        _glyphTextures[i]->setSourceFormat(GL_RGBA);
        _glyphTextures[i]->setSourceType(GL_FLOAT);
        _glyphTextures[i]->setFilter(osg::Texture::MIN_FILTER, osg::Texture::NEAREST);
        _glyphTextures[i]->setFilter(osg::Texture::MAG_FILTER, osg::Texture::NEAREST);
        _glyphTextures[i]->setResizeNonPowerOfTwoHint(false);
        _glyphTextures[i]->setUnRefImageDataAfterApply(false);
        _geodes[i]->getStateSet()->setTextureAttribute(2, _glyphTextures[i].get());
    }
    _state->addUniform(new osg::Uniform("loa_labelGlyphs", 2));
}

StreetLabels::~StreetLabels() = default;

void StreetLabels::draw(osgUtil::CullVisitor& cv, const std::vector<Label>& labels, const Parameters& p,
                        const View& view, osg::Texture2D* frontDepth, float zNear, float zFar, bool ortho)
{
    if (labels.empty()) return;
    const unsigned b = _frame++ % 2;
    osg::Geometry& g = *_geometries[b];
    osg::Vec2Array& pos = *static_cast<osg::Vec2Array*>(g.getVertexArray());
    osg::Vec2Array& tex = *static_cast<osg::Vec2Array*>(g.getTexCoordArray(0));
    osg::Vec4Array& centre = *static_cast<osg::Vec4Array*>(g.getTexCoordArray(1));
    osg::Vec2Array& field = *static_cast<osg::Vec2Array*>(g.getTexCoordArray(2));
    osg::Vec2Array& span = *static_cast<osg::Vec2Array*>(g.getTexCoordArray(3));
    osg::DrawElementsUInt& tris = *static_cast<osg::DrawElementsUInt*>(g.getPrimitiveSet(0));
    pos.clear();
    tex.clear();
    centre.clear();
    field.clear();
    span.clear();
    tris.clear();
    std::size_t glyphCount = 0;
    for (const Label& l : labels)
        glyphCount += l.glyphs.size();
    const int rowTexels = 1024;
    const int rows = int((glyphCount + rowTexels - 1) / rowTexels);
    osg::Image& centres = *_glyphImages[b];
    centres.allocateImage(rowTexels, std::max(1, rows), 1, GL_RGBA, GL_FLOAT);
    centres.setInternalTextureFormat(GL_RGBA32F_ARB);
    float* texel = reinterpret_cast<float*>(centres.data());
    std::fill(texel, texel + std::size_t(rowTexels) * std::size_t(std::max(1, rows)) * 4u, 0.0f);
    for (const Label& l : labels)
        for (const PlacedGlyph& pg : l.glyphs)
        {
            texel[0] = float(pg.centre.x());
            texel[1] = float(pg.centre.y());
            texel[2] = float(pg.depth);
            texel += 4;
        }
    centres.dirty();
    _glyphTextures[b]->setImage(&centres);
    std::size_t firstGlyph = 0;
    const float spread = float(_font->getParameters().spread);
    for (const Label& l : labels)
    {
        // The label's glyphs in the centres texture: a glyph is drawn only where all of them are
        // in view, so a label partly behind a building or a tree is hidden whole, not cut.
        const osg::Vec2 labelSpan(float(firstGlyph), float(l.glyphs.size()));
        firstGlyph += l.glyphs.size();
        for (const PlacedGlyph& pg : l.glyphs)
        {
            const SignedDistanceFont::Glyph* glyph = _font->glyph(pg.code);
            if (!glyph || glyph->blank) continue;
            osg::Vec2d q[4];
            glyphQuad(pg, l.size, *_font, q);
            const osg::Vec2f uv[4] = {glyph->texMin, osg::Vec2f(glyph->texMax.x(), glyph->texMin.y()),
                                      glyph->texMax, osg::Vec2f(glyph->texMin.x(), glyph->texMax.y())};
            // Field texels per window pixel, for the halo's width and the outline's filter.
            const float texelsPerPixel = _font->texelsPerEm() / float(l.size);
            const unsigned base = unsigned(pos.size());
            for (int i = 0; i < 4; ++i)
            {
                pos.push_back(osg::Vec2(float(q[i].x()), float(q[i].y())));
                tex.push_back(uv[i]);
                centre.push_back(
                    osg::Vec4(float(pg.centre.x()), float(pg.centre.y()), float(pg.depth), l.opacity));
                // The widest halo the field holds: its outer texel is spread - 1/2 texels from the
                // outline and the filter reaches half a pixel beyond the halo's edge.
                field.push_back(osg::Vec2(texelsPerPixel / (2.0f * spread),
                                          std::max(0.0f, (spread - 1.0f) / texelsPerPixel - 0.5f)));
                span.push_back(labelSpan);
            }
            for (unsigned k : {0u, 1u, 2u, 0u, 2u, 3u})
                tris.push_back(base + k);
        }
    }
    pos.dirty();
    tex.dirty();
    centre.dirty();
    field.dirty();
    span.dirty();
    tris.dirty();
    g.dirtyBound();
    osg::StateSet& ss = *_geodes[b]->getStateSet();
    setUniform(ss, "loa_labelViewport", osg::Vec2f(float(view.width), float(view.height)));
    setUniform(ss, "loa_labelColor", p.color);
    setUniform(ss, "loa_labelHalo", p.halo);
    setUniform(ss, "loa_labelHaloPixels", p.haloPixels);
    setUniform(ss, "loa_labelDepthRange", osg::Vec2f(zNear, zFar));
    setUniform(ss, "loa_labelOrthographic", ortho);
    setUniform(ss, "loa_labelHasDepth", frontDepth != nullptr);
    if (frontDepth) ss.setTextureAttribute(1, frontDepth);
    cv.pushStateSet(_state.get());
    _geodes[b]->accept(cv);
    cv.popStateSet();
}

} // namespace osgLoA
