// Included (#pragma include "loa_structure_tensor.glsl") by the flow-guided filters: the twin of
// osgLoA::StructureTensor::flowOf. Of a tensor (E, F, G): (t.x, t.y, A, phi), t the unit minor
// eigenvector (the edge tangent) with t.y > 0 (or t.y = 0, t.x > 0), A = (l1 - l2) / (l1 + l2)
// the anisotropy, phi the angle of the major eigenvector; t = (0, 1), A = 0, phi = 0 where the
// tensor is isotropic.
vec4 loa_flowOfTensor(vec3 efg)
{
    float E = efg.x, F = efg.y, G = efg.z;
    float root = sqrt((E - G) * (E - G) + 4.0 * F * F);
    float l1 = 0.5 * (E + G + root);
    float l2 = 0.5 * (E + G - root);
    if (!(root > 1e-9 * (l1 + l2)) || !(l1 + l2 > 0.0)) return vec4(0.0, 1.0, 0.0, 0.0);
    vec2 g = E >= G ? vec2(l1 - G, F) : vec2(F, l1 - E);
    g /= sqrt(dot(g, g));
    vec2 t = vec2(-g.y, g.x);
    if (t.y < 0.0 || (t.y == 0.0 && t.x < 0.0)) t = -t;
    return vec4(t, root / (l1 + l2), atan(-t.x, t.y));
}
