#version 450 compatibility
// The full-screen pass of post-process filtering (osgLoA::PostProcessFiltering, paper 000 Eq. 1):
// writes the filtered frame F[K (T * P)], texel for pixel (the texture has the viewport's size
// and nearest filtering, so pixel centres read exactly one texel).
uniform sampler2D loa_postprocess_frame;
in vec2 loa_postprocess_texCoord;
layout(location = 0) out vec4 loa_postprocess_color;

void main()
{
    loa_postprocess_color = texture(loa_postprocess_frame, loa_postprocess_texCoord);
}
