#version 330 core
// Texture-object histogram (paper 003, osgLoA::TextureHistogram::texelWeightsGpu): a triangle
// drawn in texture space. loa_position is the vertex's position in the viewport, in texels
// (already snapped to 1/256 texel on the CPU); loa_weight is the triangle's P^o * P^t.
layout(location = 0) in vec2 loa_position;
layout(location = 1) in float loa_weight;
uniform vec2 loa_viewportSize; // viewport width and height in texels
flat out float loa_triangleWeight;

void main()
{
    gl_Position = vec4(loa_position * (2.0 / loa_viewportSize) - 1.0, 0.0, 1.0);
    loa_triangleWeight = loa_weight;
}
