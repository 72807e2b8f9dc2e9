#version 450 compatibility
// Stencil-routed A-buffer (osgLoA::StencilRoutedABuffer; Myers & Bavoil 2007): what a routed
// draw writes. The fragment's straight-alpha colour goes to colour output 0 (RGBA8, one sample
// of the current layer, chosen by the per-sample stencil test); its depth is the fixed-function
// window depth (gl_FragCoord.z) written to the layer's depth-stencil sample. Fragments without
// alpha are discarded, so they take no sample.
layout(location = 0) out vec4 loa_abufferColorOut;

void loa_abufferWrite(vec4 straightAlphaColor)
{
    if (!(straightAlphaColor.a > 0.0))
        discard;
    loa_abufferColorOut = clamp(straightAlphaColor, 0.0, 1.0);
}
