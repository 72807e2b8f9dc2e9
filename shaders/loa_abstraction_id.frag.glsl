#version 450 compatibility
// Object-ID pass (paper 001 §4.2, paper 002 §3): every object in its unique colour, flat and
// unlit. Target 0: the object's number (1-based index of osgLoA::AbstractionNode's object table)
// as 24 bits in RGB, exact in RGBA8; target 1: the object's importance (R) and scenario
// weight (G); target 2: the view-space normal and depth (silhouettes between objects only where
// the surface is discontinuous).
uniform vec4 loa_objectId = vec4(0.0);
uniform vec4 loa_objectImportance = vec4(0.0); // component loa_abstraction_slot is this node's
uniform vec4 loa_objectWeight = vec4(0.0);
uniform int loa_abstraction_slot = 0; // nested abstraction nodes share the objects' uniforms

in vec2 loa_texCoord;
in vec4 loa_color;
in float loa_gouraud;
in vec3 loa_objectPosition;
in vec3 loa_objectNormal;
in vec4 loa_viewSurface;

layout(location = 0) out vec4 loa_idColor;
layout(location = 1) out vec4 loa_objectData;
layout(location = 2) out vec4 loa_surface; // view-space normal, view depth (silhouettes)

bool loa_materialCovers(vec2 texCoord, vec4 color); // loa_material_alpha.frag.glsl

void main()
{
    if (!loa_materialCovers(loa_texCoord, loa_color))
        discard;
    loa_idColor = loa_objectId;
    loa_objectData =
        vec4(loa_objectImportance[loa_abstraction_slot], loa_objectWeight[loa_abstraction_slot], 0.0, 1.0);
    loa_surface = vec4(normalize(loa_viewSurface.xyz), loa_viewSurface.w);
}
