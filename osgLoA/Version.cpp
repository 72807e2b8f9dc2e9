#include <osgLoA/Version>

#define OSGLOA_STR2(x) #x
#define OSGLOA_STR(x) OSGLOA_STR2(x)

extern "C"
{
    const char* osgLoAGetVersion()
    {
        return OSGLOA_STR(OSGLOA_VERSION_MAJOR) "." OSGLOA_STR(OSGLOA_VERSION_MINOR) "." OSGLOA_STR(
            OSGLOA_VERSION_PATCH);
    }
    const char* osgLoAGetLibraryName()
    {
        return "osgLoA Library";
    }
}
