#version 450 compatibility
// Graphic style "blueprint" (osgLoA::GraphicStyle, docs/styles.md): a flat blue ground, lit
// slightly; the white edges are the compositor's (edge colour white, strength 1).
uniform vec3 loa_lightDirection = vec3(0.3, 0.5, 0.8); // towards the light, view space
uniform vec3 loa_blueprint_color = vec3(31.0, 78.0, 140.0) / 255.0;
uniform float loa_blueprint_ambient = 0.8;

vec4 loa_styleColor(vec3 scenePosition, vec3 viewPosition, vec3 viewNormal, vec2 texCoord, vec4 color)
{
    float ambient = loa_blueprint_ambient;
    float diffuse = max(dot(viewNormal, normalize(loa_lightDirection)), 0.0);
    return vec4(loa_blueprint_color * (ambient + (1.0 - ambient) * diffuse), color.a);
}
