#version 450 compatibility
// Graphic style "object-edges" (paper 004 §3.2.3: generic features with "edge enhancement in
// image-space [ND03] and object-space [DW03]"; osgLoA::ObjectSpaceEdges): the feature edges of
// the geometry itself, found in object space, drawn as lines of constant width on screen.
// ObjectSpaceEdges::prepare gives every triangle of a generic feature its own corners (texture
// unit 5: the corner's one-hot barycentric coordinate, and in w the mask of the triangle's edges
// without exactly one neighbour: boundaries and non-manifold edges; bit k for the edge opposite
// corner k) and the normals of the faces beyond its edges (units 6 and 7, octahedral-encoded, 9
// where there is none). Here, per frame, an edge is a crease where the two faces' normals differ
// by more than loa_objectEdges_creaseDegrees, and a silhouette where the triangle and its
// neighbour face the eye differently (the face's own normal is its corners' cross product, so the
// winding must agree with the neighbour's: ObjectSpaceEdges::prepare stores neighbours' normals
// from their own windings). Each corner gets its
// distance in pixels to the opposite edge (noperspective), so the fragment stage knows its
// distance to each edge of its triangle (Baerentzen et al. 2006's single-pass wireframe).
// Drawables without edge data (loa_objectEdgesData false: other features) pass through with no
// edge.
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;

#pragma include "loa_geometry_stage.glsl"
in vec4 loa_vsEdgeData0[];
in vec4 loa_vsEdgeData1[];
in vec4 loa_vsEdgeData2[];

noperspective out vec3 loa_edgeDistance; // pixels to the edges opposite corners 0, 1, 2
flat out int loa_edgeMask;               // bit k: the edge opposite corner k is drawn
flat out int loa_edgeFull;               // bit k: ... at full width (silhouettes, boundaries:
                                         // only this side of them is drawn)

uniform float loa_viewportHeight = 1080.0;
uniform float loa_viewportWidth = 1920.0;
uniform float loa_objectEdges_creaseDegrees = 30.0;
uniform bool loa_objectEdgesData = false; // this drawable has edge data (ObjectSpaceEdges::prepare)

vec3 loa_octDecode(vec2 e)
{
    vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
    if (n.z < 0.0)
        n.xy = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
    return normalize(n);
}

void main()
{
    // The corner order the data was written in: corner k has its one-hot coordinate k.
    int mask = 0, full = 0;
    bool prepared = loa_objectEdgesData;
    vec3 distance = vec3(0.0);
    if (prepared)
    {
        mask = int(loa_vsEdgeData0[0].w + 0.5) & 7; // boundaries
        full = mask;
        // The face's normal and its side towards the eye, in view space.
        vec3 a = loa_vsViewPosition[0], b = loa_vsViewPosition[1], c = loa_vsViewPosition[2];
        // Under a mirroring transform (negative determinant) the corners' winding turns over while
        // the normal matrix keeps the neighbours' normals outward: turn the face's back.
        vec3 face = normalize(cross(b - a, c - a)) * (determinant(mat3(gl_ModelViewMatrix)) < 0.0 ? -1.0 : 1.0);
        bool ortho = gl_ProjectionMatrix[3][3] == 1.0;
        vec2 adjacent[3] = vec2[3](loa_vsEdgeData1[0].xy, loa_vsEdgeData1[0].zw, loa_vsEdgeData2[0].xy);
        vec3 corners[3] = vec3[3](a, b, c);
        float creaseCos = cos(radians(loa_objectEdges_creaseDegrees));
        for (int k = 0; k < 3; ++k)
        {
            if (adjacent[k].x > 8.0)
                continue; // no single neighbour: a boundary, in the mask already
            vec3 n = normalize(gl_NormalMatrix * loa_octDecode(adjacent[k]));
            vec3 mid = 0.5 * (corners[(k + 1) % 3] + corners[(k + 2) % 3]);
            vec3 toEye = ortho ? vec3(0.0, 0.0, 1.0) : -mid;
            if ((dot(face, toEye) > 0.0) != (dot(n, toEye) > 0.0))
            {
                mask |= 1 << k;
                full |= 1 << k;
            }
            else if (dot(face, n) < creaseCos)
                mask |= 1 << k;
        }
        // Window positions and each corner's distance to the opposite edge.
        vec2 viewport = vec2(loa_viewportWidth, loa_viewportHeight);
        vec2 w[3];
        for (int k = 0; k < 3; ++k)
            w[k] = gl_in[k].gl_Position.xy / gl_in[k].gl_Position.w * 0.5 * viewport;
        float area = abs((w[1].x - w[0].x) * (w[2].y - w[0].y) - (w[2].x - w[0].x) * (w[1].y - w[0].y));
        for (int k = 0; k < 3; ++k)
        {
            float base = length(w[(k + 2) % 3] - w[(k + 1) % 3]);
            distance[k] = base > 0.0 ? area / base : 0.0;
        }
        // Corners behind the eye make window positions meaningless: no lines there.
        if (gl_in[0].gl_Position.w <= 0.0 || gl_in[1].gl_Position.w <= 0.0 || gl_in[2].gl_Position.w <= 0.0)
            mask = 0;
    }
    for (int i = 0; i < 3; ++i)
    {
        loa_copyCorner(i);
        // Corner i is at distance 0 from the two edges through it and at its height from the
        // opposite one; interpolated linearly in the window.
        vec3 d = vec3(0.0);
        d[i] = distance[i];
        loa_edgeDistance = d;
        loa_edgeMask = mask;
        loa_edgeFull = full;
        gl_Position = gl_in[i].gl_Position;
        EmitVertex();
    }
    EndPrimitive();
}
