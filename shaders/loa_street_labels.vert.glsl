#version 450 compatibility
// Street labels (osgLoA::StreetLabels): glyph quads given in window pixels from the viewport's
// origin.
uniform vec2 loa_labelViewport; // width, height in pixels

out vec2 loa_atlasCoord;
flat out vec4 loa_glyphCentre; // the glyph's centre on the line (pixels), the street's window depth there, the label's opacity
flat out vec2 loa_field;       // field units per pixel, the widest halo the field holds (pixels)
flat out ivec2 loa_labelSpan;  // the label's first glyph in loa_labelGlyphs, its glyph count

void main()
{
    loa_atlasCoord = gl_MultiTexCoord0.xy;
    loa_glyphCentre = gl_MultiTexCoord1;
    loa_field = gl_MultiTexCoord2.xy;
    loa_labelSpan = ivec2(gl_MultiTexCoord3.xy + 0.5);
    gl_Position = vec4(gl_Vertex.xy / loa_labelViewport * 2.0 - 1.0, 0.0, 1.0);
}
