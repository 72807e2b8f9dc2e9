#version 450 compatibility
// Plain textured, lit rendering: texture x vertex colour x (ambient + diffuse) from one
// directional light given in view space.
uniform sampler2D loa_baseTexture;
uniform bool loa_hasTexture = true;
uniform vec3 loa_lightDirection = vec3(0.3, 0.5, 0.8); // towards the light, view space
uniform float loa_ambient = 0.35;

in vec3 loa_viewNormal;
in vec3 loa_viewPosition;
in vec2 loa_texCoord;
in vec4 loa_color;

layout(location = 0) out vec4 loa_fragColor;

void main()
{
    vec3 n = normalize(loa_viewNormal);
    if (!gl_FrontFacing)
        n = -n;
    float diffuse = max(dot(n, normalize(loa_lightDirection)), 0.0);
    vec4 base = loa_color;
    if (loa_hasTexture)
        base *= texture(loa_baseTexture, loa_texCoord);
    loa_fragColor = vec4(base.rgb * (loa_ambient + (1.0 - loa_ambient) * diffuse), base.a);
}
