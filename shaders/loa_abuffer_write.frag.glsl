#version 450 compatibility
// Stencil-routed A-buffer (osgLoA::StencilRoutedABuffer; Myers & Bavoil 2007): what a routed
// draw writes. The fragment's straight-alpha colour goes to colour output 0 (RGBA8, one sample
// of the current layer, chosen by the per-sample stencil test); its depth is the window depth at
// the pixel centre (gl_FragCoord.z), written explicitly: multisampled rasterization would
// otherwise store the depth interpolated at the routed sample's position, and two styles of one
// surface routed to different samples would differ in depth by the surface's slope, too much to
// be merged as one surface at grazing angles (the background showed through as speckles). It is
// then the very depth the G-buffer pass stores. Fragments whose alpha rounds to 0 in RGBA8 are
// discarded, so they take no sample (a stored alpha of 0 would be an empty fragment).
layout(location = 0) out vec4 loa_abufferColorOut;

void loa_abufferWrite(vec4 straightAlphaColor)
{
    if (!(straightAlphaColor.a >= 0.5 / 255.0))
        discard;
    loa_abufferColorOut = clamp(straightAlphaColor, 0.0, 1.0);
    gl_FragDepth = gl_FragCoord.z;
}
