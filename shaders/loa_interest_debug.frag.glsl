#version 450 compatibility
// The interest debug view (paper 004 Figure 5): black = high detail (interest 1), white = low
// detail (interest 0), for the feature's first matching configuration (or the one chosen
// with loa_debugConfiguration >= 0). Features no configuration matches are drawn red.
float loa_featureInterestOf(int j, vec3 p);
uniform int loa_featureMatches;
uniform int loa_numConfigurations;
uniform int loa_debugConfiguration = -1;

in vec3 loa_scenePosition;
layout(location = 0) out vec4 loa_fragColor;

void main()
{
    int j = loa_debugConfiguration;
    if (j < 0)
    {
        for (int k = loa_numConfigurations - 1; k >= 0; --k)
            if ((loa_featureMatches & (1 << k)) != 0)
                j = k;
    }
    if (j < 0 || (loa_featureMatches & (1 << j)) == 0)
    {
        loa_fragColor = vec4(0.8, 0.1, 0.1, 1.0);
        return;
    }
    float interest = loa_featureInterestOf(j, loa_scenePosition);
    loa_fragColor = vec4(vec3(1.0 - interest), 1.0);
}
