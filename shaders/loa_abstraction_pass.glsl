// The interface of the abstraction's object-space passes (loa_abstraction_object.vert.glsl's
// outputs and the colour output), included by loa_abstraction_shading.frag.glsl and
// loa_abstraction_unshaded.frag.glsl.
in vec2 loa_texCoord;
in vec4 loa_color;
in float loa_gouraud;
in vec3 loa_objectPosition;
in vec3 loa_objectNormal;

layout(location = 0) out vec4 loa_fragColor;

bool loa_materialCovers(vec2 texCoord, vec4 color); // loa_material_alpha.frag.glsl
