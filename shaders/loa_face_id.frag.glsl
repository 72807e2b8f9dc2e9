#version 450 compatibility
// ID buffer for viewpoint entropy: writes the face id colour verbatim (no lighting, no
// texturing); the RGBA8 target stores it exactly (c/255 converts back to c).
flat in vec4 loa_faceId;

layout(location = 0) out vec4 loa_fragColor;

void main()
{
    loa_fragColor = loa_faceId;
}
