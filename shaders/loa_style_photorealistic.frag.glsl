#version 450 compatibility
// Graphic style "photorealistic" (osgLoA::GraphicStyle, docs/styles.md): the model's own
// materials and textures, lit as loa_plain.frag.glsl lights them: texture x base colour x
// (ambient + (1 - ambient) diffuse) from one directional light given in view space.
// The base colour is the vertex colour, which is the OSG material's diffuse colour wherever
// fixed-function lighting would use it (osg::Material::apply sets the current colour to the
// diffuse colour; with colour mode AMBIENT_AND_DIFFUSE the colour array is the diffuse
// colour). For a material with colour mode OFF on a geometry with a colour array, set
// loa_photorealistic_materialDiffuse to use gl_FrontMaterial.diffuse instead.
uniform sampler2D loa_baseTexture;
uniform bool loa_hasTexture; // the drawable has a texture on unit 0 (TransitionRenderer::bind)
uniform vec3 loa_lightDirection = vec3(0.3, 0.5, 0.8); // towards the light, view space
uniform float loa_photorealistic_ambient = 0.35;
uniform bool loa_photorealistic_materialDiffuse = false;

vec4 loa_styleColor(vec3 scenePosition, vec3 viewPosition, vec3 viewNormal, vec2 texCoord, vec4 color)
{
    vec4 base = loa_photorealistic_materialDiffuse ? gl_FrontMaterial.diffuse : color;
    if (loa_hasTexture)
        base *= texture(loa_baseTexture, texCoord);
    float ambient = loa_photorealistic_ambient;
    float diffuse = max(dot(viewNormal, normalize(loa_lightDirection)), 0.0);
    return vec4(base.rgb * (ambient + (1.0 - ambient) * diffuse), base.a);
}
