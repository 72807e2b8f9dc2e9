#version 450 compatibility
// OSG's fixed-function pipeline, per fragment, for the graphic styles that draw the model as it
// is (photorealistic) or its abstraction with the model's own lighting (abstract). Linked into
// every style program (GraphicStyle::shaderNames, TransitionRenderer). The model's state reaches
// it through osgLoA::FixedFunctionUniforms.
uniform int loa_texEnvMode = 0; // 0 modulate, 1 replace, 2 decal, 3 add, 4 blend
uniform bool loa_lighting = true;  // GL_LIGHTING of the model's state
uniform int loa_colorMaterial = 1; // 0 off, 1 ambient+diffuse, 2 ambient, 3 diffuse, 4 emission, 5 specular

// The fixed-function lighting of light 0 for the front material; `normal` is the vertex normal
// as given (not turned towards the viewer: one-sided lighting, OSG's default).
vec4 loa_fixedFunctionLighting(vec3 viewPosition, vec3 normal, vec4 color)
{
    if (!loa_lighting)
        return color;
    vec4 ambient = loa_colorMaterial == 1 || loa_colorMaterial == 2 ? color : gl_FrontMaterial.ambient;
    vec4 diffuse = loa_colorMaterial == 1 || loa_colorMaterial == 3 ? color : gl_FrontMaterial.diffuse;
    vec4 emission = loa_colorMaterial == 4 ? color : gl_FrontMaterial.emission;
    vec4 specular = loa_colorMaterial == 5 ? color : gl_FrontMaterial.specular;
    vec4 position = gl_LightSource[0].position;
    vec3 toLight = position.w == 0.0 ? position.xyz : position.xyz / position.w - viewPosition;
    float attenuation = 1.0;
    if (position.w != 0.0)
    {
        float d = length(toLight);
        attenuation = 1.0 / max(gl_LightSource[0].constantAttenuation + gl_LightSource[0].linearAttenuation * d +
                                    gl_LightSource[0].quadraticAttenuation * d * d,
                                1.0e-6);
    }
    vec3 l = normalize(toLight);
    vec3 n = normalize(normal);
    float nDotL = max(dot(n, l), 0.0);
    vec3 c = emission.rgb + ambient.rgb * gl_LightModel.ambient.rgb +
             attenuation * (ambient.rgb * gl_LightSource[0].ambient.rgb +
                            nDotL * diffuse.rgb * gl_LightSource[0].diffuse.rgb);
    if (nDotL > 0.0)
    {
        float s = max(dot(n, normalize(l + vec3(0.0, 0.0, 1.0))), 0.0); // non-local viewer
        c += attenuation * (s > 0.0 ? pow(s, gl_FrontMaterial.shininess) : 0.0) * specular.rgb *
             gl_LightSource[0].specular.rgb;
    }
    return vec4(clamp(c, 0.0, 1.0), diffuse.a);
}

// The fixed-function texture environment of unit 0 (GL 1.5 table 3.22; BLEND uses the
// environment colour's default, black, so it is MODULATE's complement).
vec4 loa_fixedFunctionTexEnvMode(int mode, vec4 fragment, vec4 texel)
{
    if (mode == 1)
        return texel;
    if (mode == 2)
        return vec4(mix(fragment.rgb, texel.rgb, texel.a), fragment.a);
    if (mode == 3)
        return vec4(min(fragment.rgb + texel.rgb, vec3(1.0)), fragment.a * texel.a);
    if (mode == 4)
        return vec4(fragment.rgb * (1.0 - texel.rgb), fragment.a * texel.a);
    return fragment * texel;
}

vec4 loa_fixedFunctionTexEnv(vec4 fragment, vec4 texel)
{
    return loa_fixedFunctionTexEnvMode(loa_texEnvMode, fragment, texel);
}

