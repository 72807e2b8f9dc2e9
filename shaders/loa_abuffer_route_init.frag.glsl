#version 450 compatibility
// osgLoA::StencilRoutedABuffer: the stencil initialization and overflow-count passes write only
// stencil or nothing (colour writes are masked off).
layout(location = 0) out vec4 loa_fragColor;

void main()
{
    loa_fragColor = vec4(0.0);
}
