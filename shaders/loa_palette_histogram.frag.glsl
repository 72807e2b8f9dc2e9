#version 330 core
// Texture-object histogram: every covered texel receives the triangle's P^o * P^t; additive
// blending (GL_ONE, GL_ONE) into an R32F target sums the triangles covering it.
flat in float loa_triangleWeight;
layout(location = 0) out vec4 loa_fragWeight;

void main()
{
    loa_fragWeight = vec4(loa_triangleWeight, 0.0, 0.0, 0.0);
}
