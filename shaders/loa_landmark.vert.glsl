#version 450 compatibility
// Landmark deformation (paper 004 §3.2.2, Figure 7): scaling, rotation to the best view,
// flattening and cylindrical billboard of landmarks, blended with the original vertices; sinking
// of non-landmarks. Positions and normals are in the LoA node's local ("scene") coordinates, Z up.
// The whole deformation of a feature in a frame is one affine map computed on the CPU
// (osgLoA::LandmarkDeformation::computeFrame, its CPU twin), so the shader only applies it.
//
// Scene-wide (LandmarkDeformation::applyScenario on the LoA node's state):
uniform bool loa_deformEnabled = false; // false: no deformation (the scenario has none)
// Per feature (LandmarkDeformation::applyFeature on the feature's state; the scene-wide state
// holds the identity for features that are not set):
uniform mat4 loa_deformMatrix = mat4(1.0);       // scene -> deformed scene
uniform mat3 loa_deformNormalMatrix = mat3(1.0); // cofactor of its linear part

// The deformed scene position of a vertex.
vec3 loa_deformVertex(vec3 scenePosition)
{
    if (!loa_deformEnabled) return scenePosition;
    return (loa_deformMatrix * vec4(scenePosition, 1.0)).xyz;
}

// The deformed unit normal of a vertex (sceneNormal need not be unit length): through the
// cofactor of the deformation's linear part. A fully flattened landmark maps every normal onto
// the plane's; normals of faces that collapse to lines (zero area) vanish and keep their own
// direction instead. CPU twin: LandmarkDeformation::deformNormal.
vec3 loa_deformNormal(vec3 sceneNormal)
{
    if (!loa_deformEnabled) return normalize(sceneNormal);
    mat3 m = loa_deformNormalMatrix;
    float frobenius = dot(m[0], m[0]) + dot(m[1], m[1]) + dot(m[2], m[2]);
    vec3 n = m * sceneNormal;
    if (!(dot(n, n) > 1e-8 * frobenius * dot(sceneNormal, sceneNormal))) n = sceneNormal;
    return normalize(n);
}
